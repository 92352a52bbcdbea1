//! The referee's two CRCs, written for speed without `unsafe`: the header CRC-8 by slicing-by-4
//! (the header is four bytes: four independent lookups instead of a chain of four), the frame
//! CRC-16/MCRF4XX by slicing-by-16 with no byte-wise loop at all.
//!
//! Both are reflected CRCs, whose register shifts right. The byte table `T0[x]` is the register
//! after feeding byte `x` into a zero register; `Tk = T0` followed by `k` zero bytes. Because a
//! CRC is linear, sixteen bytes `b0..b15` fed into register `r` give
//! `T15[b0 ^ r0] ^ T14[b1 ^ r1] ^ T13[b2] ^ ... ^ T0[b15]` (`r0`, `r1` the register's bytes).
//!
//! The first `n % 16` bytes of a frame do not fill a block. A zero register stays zero over zero
//! bytes, so the initial value is folded into the first data bytes (xor) and the leading bytes
//! are fed as one block padded with zeros in front: one more block, but no byte loop whose trip
//! count changes with every frame (a branch mispredicted once per frame).

/// The referee header CRC-8 (poly 0x31 reflected = 0x8C, register starting at 0xFF).
const CRC8_POLY: u8 = 0x8C;
const CRC8_INIT: u8 = 0xFF;
/// CRC-16/MCRF4XX (poly 0x1021 reflected = 0x8408, register starting at 0xFFFF).
const CRC16_POLY: u16 = 0x8408;
const CRC16_INIT: u16 = 0xFFFF;

const fn crc8_tables() -> [[u8; 256]; 4] {
    let mut t = [[0u8; 256]; 4];
    let mut x = 0;
    while x < 256 {
        let mut r = x as u8;
        let mut bit = 0;
        while bit < 8 {
            r = if r & 1 != 0 {
                (r >> 1) ^ CRC8_POLY
            } else {
                r >> 1
            };
            bit += 1;
        }
        t[0][x] = r;
        x += 1;
    }
    let mut k = 1;
    while k < 4 {
        let mut x = 0;
        while x < 256 {
            // One more zero byte: an 8-bit register is shifted out whole.
            t[k][x] = t[0][t[k - 1][x] as usize];
            x += 1;
        }
        k += 1;
    }
    t
}

const fn crc16_tables() -> [[u16; 256]; 16] {
    let mut t = [[0u16; 256]; 16];
    let mut x = 0;
    while x < 256 {
        let mut r = x as u16;
        let mut bit = 0;
        while bit < 8 {
            r = if r & 1 != 0 {
                (r >> 1) ^ CRC16_POLY
            } else {
                r >> 1
            };
            bit += 1;
        }
        t[0][x] = r;
        x += 1;
    }
    let mut k = 1;
    while k < 16 {
        let mut x = 0;
        while x < 256 {
            let prev = t[k - 1][x];
            t[k][x] = (prev >> 8) ^ t[0][(prev & 0xFF) as usize];
            x += 1;
        }
        k += 1;
    }
    t
}

static CRC8_T: [[u8; 256]; 4] = crc8_tables();
static CRC16_T: [[u16; 256]; 16] = crc16_tables();

/// The referee header CRC-8 of the four header bytes.
#[inline(always)]
pub fn crc8_header(h: [u8; 4]) -> u8 {
    CRC8_T[3][usize::from(h[0] ^ CRC8_INIT)]
        ^ CRC8_T[2][usize::from(h[1])]
        ^ CRC8_T[1][usize::from(h[2])]
        ^ CRC8_T[0][usize::from(h[3])]
}

/// Feeds one 16-byte block into register `r`.
#[inline(always)]
fn block16(r: u16, b: [u8; 16]) -> u16 {
    let [r0, r1] = r.to_le_bytes();
    let t = &CRC16_T;
    (t[15][usize::from(b[0] ^ r0)]
        ^ t[14][usize::from(b[1] ^ r1)]
        ^ t[13][usize::from(b[2])]
        ^ t[12][usize::from(b[3])])
        ^ (t[11][usize::from(b[4])]
            ^ t[10][usize::from(b[5])]
            ^ t[9][usize::from(b[6])]
            ^ t[8][usize::from(b[7])])
        ^ (t[7][usize::from(b[8])]
            ^ t[6][usize::from(b[9])]
            ^ t[5][usize::from(b[10])]
            ^ t[4][usize::from(b[11])])
        ^ (t[3][usize::from(b[12])]
            ^ t[2][usize::from(b[13])]
            ^ t[1][usize::from(b[14])]
            ^ t[0][usize::from(b[15])])
}

/// CRC-16/MCRF4XX of `data[..n]` (`1 <= n <= data.len()`).
///
/// Reading a whole first block is cheaper than assembling a short one, so `data` may run past
/// the covered bytes (a decoder passes the rest of its input); only `data[..n]` is used.
#[inline(always)]
pub fn crc16(data: &[u8], n: usize) -> u16 {
    let Some(covered) = data.get(..n).filter(|c| !c.is_empty()) else {
        return CRC16_INIT;
    };
    // `lead` in 1..=16: the leading bytes that do not make a whole block, or a whole block.
    let lead = (n - 1) % 16 + 1;
    let first = match data.first_chunk::<16>() {
        Some(block) => u128::from_le_bytes(*block),
        None => {
            let mut block = [0u8; 16];
            block[..covered.len()].copy_from_slice(covered);
            u128::from_le_bytes(block)
        }
    };
    // Keep the first `lead` bytes, moved to the end of the block; fold the initial register
    // into the first two of them. With `lead == 1` the register's high byte falls off the
    // block: it is what the register still holds after the block, xored in below.
    let pad = 8 * (16 - lead as u32);
    let keep = first << pad;
    let init = u128::from(CRC16_INIT) << pad;
    let mut r = block16(0, (keep ^ init).to_le_bytes());
    r ^= (u32::from(CRC16_INIT) >> (8 * lead.min(2) as u32)) as u16;
    for block in covered[lead..].chunks_exact(16) {
        if let Ok(block) = <[u8; 16]>::try_from(block) {
            r = block16(r, block);
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workload::{Rng, referee_crc8, referee_crc16};

    #[test]
    fn check_values() {
        assert_eq!(crc16(b"123456789", 9), 0x6F91);
        assert_eq!(crc8_header([0xA5, 0x03, 0x00, 0x00]), 0x27);
    }

    #[test]
    fn crc16_matches_the_crc_crate_for_every_length_and_overrun() {
        let mut rng = Rng::new(7);
        let buf: Vec<u8> = (0..300).map(|_| rng.byte()).collect();
        for n in 1..200 {
            for extra in [0, 1, 15, 16, 40] {
                assert_eq!(
                    crc16(&buf[..n + extra], n),
                    referee_crc16(&buf[..n]),
                    "n {n} +{extra}"
                );
            }
        }
    }

    #[test]
    fn crc8_matches_the_crc_crate() {
        let mut rng = Rng::new(8);
        for _ in 0..10_000 {
            let h = [rng.byte(), rng.byte(), rng.byte(), rng.byte()];
            assert_eq!(crc8_header(h), referee_crc8(&h));
        }
    }
}
