//! A lossy link with a simulated clock: each frame put on the wire meets the next fault of a
//! schedule (pass after a delay, drop, duplicate, corrupt), so frames arrive late, twice,
//! damaged or not at all, and out of order (a later frame with a shorter delay overtakes).

/// What happens to one frame on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fault {
    /// It arrives after this many milliseconds.
    Pass(u64),
    /// It is lost.
    Drop,
    /// It arrives twice, after each delay.
    Twice(u64, u64),
    /// It arrives after the delay with one byte (index modulo its length) XORed with the mask
    /// (never 0 or 0xFF: a mask of 0xFF turns 0x00 into 0xFF, which a sum modulo 255 misses).
    Corrupt(u64, usize, u8),
}

/// Counts of the faults the link applied.
#[derive(Debug, Clone, Copy, Default)]
pub struct Faults {
    pub frames: u64,
    pub dropped: u64,
    pub duplicated: u64,
    pub corrupted: u64,
    pub delayed: u64,
}

/// Frames in flight one way.
#[derive(Debug, Default)]
struct Lane {
    flying: Vec<(u64, u64, Vec<u8>)>,
}

/// Both directions of a link, and the fault schedule they draw from in turn.
#[derive(Debug)]
pub struct Link {
    lanes: [Lane; 2],
    schedule: Vec<Fault>,
    next: usize,
    order: u64,
    pub faults: Faults,
}

/// The lane from the requester to the responder.
pub const DOWN: usize = 0;
/// The lane from the responder to the requester.
pub const UP: usize = 1;

impl Link {
    pub fn new(schedule: Vec<Fault>) -> Self {
        Self {
            lanes: [Lane::default(), Lane::default()],
            schedule,
            next: 0,
            order: 0,
            faults: Faults::default(),
        }
    }

    /// Puts `frame` on lane `lane` at `now`; once the schedule is spent, frames pass in 1 ms.
    pub fn send(&mut self, lane: usize, now: u64, frame: &[u8]) {
        let fault = self
            .schedule
            .get(self.next)
            .copied()
            .unwrap_or(Fault::Pass(1));
        self.next += 1;
        self.faults.frames += 1;
        let mut put = |at: u64, bytes: Vec<u8>, order: &mut u64| {
            *order += 1;
            self.lanes[lane].flying.push((now + at, *order, bytes));
        };
        match fault {
            Fault::Pass(d) => {
                self.faults.delayed += u64::from(d > 1);
                put(d, frame.to_vec(), &mut self.order);
            }
            Fault::Drop => self.faults.dropped += 1,
            Fault::Twice(a, b) => {
                self.faults.duplicated += 1;
                put(a, frame.to_vec(), &mut self.order);
                put(b, frame.to_vec(), &mut self.order);
            }
            Fault::Corrupt(d, at, mask) => {
                self.faults.corrupted += 1;
                let mut bytes = frame.to_vec();
                let i = at % bytes.len();
                bytes[i] ^= mask;
                put(d, bytes, &mut self.order);
            }
        }
    }

    /// The frames of lane `lane` that arrive by `now`, in arrival order.
    pub fn arrived(&mut self, lane: usize, now: u64) -> Vec<Vec<u8>> {
        let flying = &mut self.lanes[lane].flying;
        let mut due: Vec<(u64, u64, Vec<u8>)> = Vec::new();
        let mut i = 0;
        while i < flying.len() {
            if flying[i].0 <= now {
                due.push(flying.swap_remove(i));
            } else {
                i += 1;
            }
        }
        due.sort_by_key(|(at, order, _)| (*at, *order));
        due.into_iter().map(|(_, _, b)| b).collect()
    }

    /// True when no frame is in flight.
    pub fn quiet(&self) -> bool {
        self.lanes.iter().all(|l| l.flying.is_empty())
    }
}
