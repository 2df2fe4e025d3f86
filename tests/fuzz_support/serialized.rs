//! Corrupted serialized FMU states: truncated, bit-flipped, extended, random, or with a number
//! overwritten and the checksum fixed.

use super::rng::Rng;

/// The FMU's checksum of serialized states (FNV-1a 64), recomputed so that corrupted bytes get
/// past it and reach the structural checks behind it.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

pub fn mutate(rng: &mut Rng, pool: &[Vec<u8>]) -> (Vec<u8>, String) {
    let mut note = String::new();
    let mut bytes = if pool.is_empty() || rng.chance(5) {
        (0..rng.below(200)).map(|_| rng.next() as u8).collect()
    } else {
        pool[rng.below(pool.len())].clone()
    };
    match rng.below(8) {
        0 | 1 => {}
        2 => bytes.truncate(rng.below(bytes.len() + 1)),
        3 => {
            if !bytes.is_empty() {
                let i = rng.below(bytes.len());
                bytes[i] ^= 1 << rng.below(8);
            }
        }
        4 => bytes.extend((0..rng.below(16)).map(|_| rng.next() as u8)),
        _ => {
            // Overwrite an 8-byte number in the body with a special value, then fix the checksum.
            // One whole number: the serialized state is the magic word, its length, the GUID's
            // length and text, then 8-byte numbers, then the checksum.
            let guid_length = bytes
                .get(16..20)
                .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
            let first = 20 + guid_length;
            if bytes.len() >= first + 16 {
                let body = bytes.len() - 8;
                let at = first + 8 * rng.below((body - first) / 8);
                // Values the FMU must refuse, or harmless ones: an accepted 1e12 Hz or a
                // 1e-300 kg would make the next doStep endless (see MAX_STEPS_PER_CALL).
                let value = rng.pick(&[
                    f64::NAN,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    -1.0,
                    0.0,
                    -0.0,
                    1.0,
                    2.0,
                    3.5,
                    6.0,
                ]);
                bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
                note = format!(", {value} at byte {at}, checksum fixed");
                let sum = fnv1a(&bytes[..body]);
                bytes[body..].copy_from_slice(&sum.to_le_bytes());
            }
        }
    }
    (bytes, note)
}
