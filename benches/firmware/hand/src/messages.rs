//! HFLink's payloads and commands by hand: the structs (PC layout, little-endian, padding sent
//! as zeros), their wire form, and the request and response enums with their ids.

/// A little-endian cursor over a payload.
pub struct Rd<'a>(&'a [u8]);

impl Rd<'_> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, rest) = self.0.split_first_chunk::<N>()?;
        self.0 = rest;
        Some(*head)
    }
    fn u8(&mut self) -> Option<u8> {
        self.take::<1>().map(|[b]| b)
    }
    fn u16(&mut self) -> Option<u16> {
        self.take().map(u16::from_le_bytes)
    }
    fn u32(&mut self) -> Option<u32> {
        self.take().map(u32::from_le_bytes)
    }
    fn f32(&mut self) -> Option<f32> {
        self.take().map(f32::from_le_bytes)
    }
    fn skip(&mut self, n: usize) -> Option<()> {
        self.0 = self.0.get(n..)?;
        Some(())
    }
}

/// A little-endian writer into a payload.
pub struct Wr<'a>(&'a mut [u8], usize);

impl Wr<'_> {
    fn put<const N: usize>(&mut self, bytes: [u8; N]) -> Option<()> {
        self.0.get_mut(self.1..self.1 + N)?.copy_from_slice(&bytes);
        self.1 += N;
        Some(())
    }
    fn u8(&mut self, v: u8) -> Option<()> {
        self.put([v])
    }
    fn u16(&mut self, v: u16) -> Option<()> {
        self.put(v.to_le_bytes())
    }
    fn u32(&mut self, v: u32) -> Option<()> {
        self.put(v.to_le_bytes())
    }
    fn f32(&mut self, v: f32) -> Option<()> {
        self.put(v.to_le_bytes())
    }
    fn zeros(&mut self, n: usize) -> Option<()> {
        self.0.get_mut(self.1..self.1 + n)?.fill(0);
        self.1 += n;
        Some(())
    }
}

/// A payload struct's wire form.
pub trait Wire: Sized {
    /// Bytes on the wire.
    const SIZE: usize;
    /// Reads the struct.
    fn get(r: &mut Rd<'_>) -> Option<Self>;
    /// Writes the struct.
    fn put(&self, w: &mut Wr<'_>) -> Option<()>;
    /// The struct from exactly `bytes`.
    fn from_bytes(bytes: &[u8]) -> Option<Self> {
        if bytes.len() != Self::SIZE {
            return None;
        }
        Self::get(&mut Rd(bytes))
    }
    /// Writes the struct at the start of `out`; the bytes written.
    fn to_bytes(&self, out: &mut [u8]) -> Option<usize> {
        let mut w = Wr(out, 0);
        self.put(&mut w)?;
        Some(w.1)
    }
}

/// Structs of `f32` fields only.
macro_rules! floats {
    ($($name:ident { $($f:ident),* })*) => {$(
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct $name { $(pub $f: f32),* }
        impl Wire for $name {
            const SIZE: usize = 4 * [$(stringify!($f)),*].len();
            fn get(r: &mut Rd<'_>) -> Option<Self> {
                Some($name { $($f: r.f32()?),* })
            }
            fn put(&self, w: &mut Wr<'_>) -> Option<()> {
                $(w.f32(self.$f)?;)*
                Some(())
            }
        }
    )*};
}

floats! {
    ChassisCoord { x, y, z }
    ChassisDofVector { servo1, servo2, servo3, servo4 }
    HeadPose { pitch, roll, yaw }
    SystemInfo { system_time, cpu_temperature, cpu_usage, battery_voltage, power_remain }
    ImuSensorData { pitch, roll, yaw, bar_altitude, magnetic_angle }
    PidParameters { p1, i1, d1, p2, i2, d2 }
}

/// One value per arm joint.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArmDofVector {
    pub servo: [f32; 8],
}

impl Wire for ArmDofVector {
    const SIZE: usize = 32;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        let mut servo = [0.0; 8];
        for s in &mut servo {
            *s = r.f32()?;
        }
        Some(ArmDofVector { servo })
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        self.servo.iter().try_for_each(|&s| w.f32(s))
    }
}

/// A GPS fix (36 bytes, padding included).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpsData {
    pub year: u16,
    pub month: u8,
    pub date: u8,
    pub hour: u8,
    pub min: u8,
    pub sec: u8,
    pub satellite_num: u8,
    pub altitude: f32,
    pub ground_speed: f32,
    pub latitude: u32,
    pub nshemi: u8,
    pub longitude: u32,
    pub ewhemi: u8,
}

impl Wire for GpsData {
    const SIZE: usize = 36;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        let (year, month, date, hour, min, sec) =
            (r.u16()?, r.u8()?, r.u8()?, r.u8()?, r.u8()?, r.u8()?);
        r.skip(1)?;
        let satellite_num = r.u8()?;
        r.skip(3)?;
        let (altitude, ground_speed, latitude, nshemi) = (r.f32()?, r.f32()?, r.u32()?, r.u8()?);
        r.skip(3)?;
        let (longitude, ewhemi) = (r.u32()?, r.u8()?);
        r.skip(3)?;
        Some(GpsData {
            year,
            month,
            date,
            hour,
            min,
            sec,
            satellite_num,
            altitude,
            ground_speed,
            latitude,
            nshemi,
            longitude,
            ewhemi,
        })
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        w.u16(self.year)?;
        [self.month, self.date, self.hour, self.min, self.sec]
            .iter()
            .try_for_each(|&b| w.u8(b))?;
        w.zeros(1)?;
        w.u8(self.satellite_num)?;
        w.zeros(3)?;
        w.f32(self.altitude)?;
        w.f32(self.ground_speed)?;
        w.u32(self.latitude)?;
        w.u8(self.nshemi)?;
        w.zeros(3)?;
        w.u32(self.longitude)?;
        w.u8(self.ewhemi)?;
        w.zeros(3)
    }
}

/// Chassis configuration (24 bytes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ChassisParameters {
    pub kind: u32,
    pub wheel_radius: f32,
    pub body_radius: f32,
    pub speed_low_filter: f32,
    pub motor_pid_t: f32,
    pub flags: [u8; 4],
}

impl Wire for ChassisParameters {
    const SIZE: usize = 24;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        Some(ChassisParameters {
            kind: r.u32()?,
            wheel_radius: r.f32()?,
            body_radius: r.f32()?,
            speed_low_filter: r.f32()?,
            motor_pid_t: r.f32()?,
            flags: r.take()?,
        })
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        w.u32(self.kind)?;
        [
            self.wheel_radius,
            self.body_radius,
            self.speed_low_filter,
            self.motor_pid_t,
        ]
        .iter()
        .try_for_each(|&v| w.f32(v))?;
        w.put(self.flags)
    }
}

/// Head configuration (48 bytes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HeadParameters {
    pub kind: u32,
    pub speed_low_filter: f32,
    pub range: HeadPose,
    pub offset: HeadPose,
    pub id: HeadPose,
    pub imu_fusion_enalbe: u8,
    pub control_enable: u8,
}

impl Wire for HeadParameters {
    const SIZE: usize = 48;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        let p = HeadParameters {
            kind: r.u32()?,
            speed_low_filter: r.f32()?,
            range: HeadPose::get(r)?,
            offset: HeadPose::get(r)?,
            id: HeadPose::get(r)?,
            imu_fusion_enalbe: r.u8()?,
            control_enable: r.u8()?,
        };
        r.skip(2)?;
        Some(p)
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        w.u32(self.kind)?;
        w.f32(self.speed_low_filter)?;
        self.range.put(w)?;
        self.offset.put(w)?;
        self.id.put(w)?;
        w.u8(self.imu_fusion_enalbe)?;
        w.u8(self.control_enable)?;
        w.zeros(2)
    }
}

/// Arm configuration (12 bytes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArmParameters {
    pub kind: u32,
    pub speed_low_filter: f32,
    pub dof: u8,
    pub imu_fusion_enalbe: u8,
    pub control_enable: u8,
}

impl Wire for ArmParameters {
    const SIZE: usize = 12;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        let p = ArmParameters {
            kind: r.u32()?,
            speed_low_filter: r.f32()?,
            dof: r.u8()?,
            imu_fusion_enalbe: r.u8()?,
            control_enable: r.u8()?,
        };
        r.skip(1)?;
        Some(p)
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        w.u32(self.kind)?;
        w.f32(self.speed_low_filter)?;
        [self.dof, self.imu_fusion_enalbe, self.control_enable]
            .iter()
            .try_for_each(|&b| w.u8(b))?;
        w.zeros(1)
    }
}

/// Motor configuration, PC layout (48 bytes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotorParameters {
    pub motor_id: u8,
    pub values: [f32; 5],
    pub pid: PidParameters,
}

impl Wire for MotorParameters {
    const SIZE: usize = 48;
    fn get(r: &mut Rd<'_>) -> Option<Self> {
        let motor_id = r.u8()?;
        r.skip(3)?;
        let mut values = [0.0; 5];
        for v in &mut values {
            *v = r.f32()?;
        }
        Some(MotorParameters {
            motor_id,
            values,
            pid: PidParameters::get(r)?,
        })
    }
    fn put(&self, w: &mut Wr<'_>) -> Option<()> {
        w.u8(self.motor_id)?;
        w.zeros(3)?;
        self.values.iter().try_for_each(|&v| w.f32(v))?;
        self.pid.put(w)
    }
}

/// A message enum: variants with their command id and optional payload struct; `decode` takes a
/// command id and the payload, `encode` writes the payload and returns the id.
macro_rules! messages {
    ($name:ident { $($id:literal $v:ident $(($t:ty))?,)* }) => {
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum $name { $($v $(($t))?,)* }
        impl $name {
            pub fn decode(id: u8, payload: &[u8]) -> Option<Self> {
                match id {
                    $($id => messages!(@get $v, payload $(, $t)?),)*
                    _ => None,
                }
            }
            pub fn encode(&self, out: &mut [u8]) -> Option<(u8, usize)> {
                match self {
                    $(messages!(@pat $v, p $(, $t)?) => Some(($id, messages!(@put p, out $(, $t)?)?)),)*
                }
            }
        }
    };
    (@get $v:ident, $p:ident) => { if $p.is_empty() { Some(Self::$v) } else { None } };
    (@get $v:ident, $p:ident, $t:ty) => { <$t>::from_bytes($p).map(Self::$v) };
    (@pat $v:ident, $p:ident) => { Self::$v };
    (@pat $v:ident, $p:ident, $t:ty) => { Self::$v($p) };
    (@put $p:ident, $out:ident) => { Some(0) };
    (@put $p:ident, $out:ident, $t:ty) => { $p.to_bytes($out) };
}

messages!(Request {
    0 ShakingHands(ChassisCoord),
    1 ReadSystemInfo,
    2 SetMotorParameters(MotorParameters),
    3 SaveMotorParameters,
    4 SetChassisParameters(ChassisParameters),
    5 SaveChassisParameters,
    6 SetHeadParameters(HeadParameters),
    7 SaveHeadParameters,
    8 SetArmParameters(ArmParameters),
    9 SaveArmParameters,
    10 SetGlobalSpeed(ChassisCoord),
    11 ReadGlobalSpeed,
    12 SetRobotSpeed(ChassisCoord),
    13 ReadRobotSpeed,
    14 SetMotorSpeed(ChassisDofVector),
    15 ReadMotorSpeed,
    16 ReadMotorMileage,
    17 ReadGlobalCoordinate,
    18 ReadRobotCoordinate,
    19 ClearCoordinateData,
    20 SetHeadState(HeadPose),
    21 ReadHeadState,
    22 SetArmState(ArmDofVector),
    23 ReadArmState,
    24 ReadImuBaseData,
    25 ReadImuFusionData,
    26 ReadGpsData,
});

messages!(Response {
    0 ShakingHands,
    1 ReadSystemInfo(SystemInfo),
    2 SetMotorParameters,
    3 SaveMotorParameters,
    4 SetChassisParameters(ChassisParameters),
    5 SaveChassisParameters,
    6 SetHeadParameters,
    7 SaveHeadParameters,
    8 SetArmParameters,
    9 SaveArmParameters,
    10 SetGlobalSpeed,
    11 ReadGlobalSpeed(ChassisCoord),
    12 SetRobotSpeed,
    13 ReadRobotSpeed(ChassisCoord),
    14 SetMotorSpeed,
    15 ReadMotorSpeed(ChassisDofVector),
    16 ReadMotorMileage(ChassisDofVector),
    17 ReadGlobalCoordinate(ChassisCoord),
    18 ReadRobotCoordinate(ChassisCoord),
    19 ClearCoordinateData,
    20 SetHeadState,
    21 ReadHeadState(HeadPose),
    22 SetArmState,
    23 ReadArmState(ArmDofVector),
    24 ReadImuBaseData(ImuSensorData),
    25 ReadImuFusionData(ImuSensorData),
    26 ReadGpsData(GpsData),
});
