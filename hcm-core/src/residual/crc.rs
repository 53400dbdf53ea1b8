//! CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), the checksum of zlib, PNG and
//! Ethernet, so that `crc32`/`zlib.crc32` on the host can check a blob too.
//!
//! Bitwise, without a table: a blob is checked once, at start-up, and 1 KiB of table
//! would cost more flash than the few microseconds it saves.

/// The reflected IEEE 802.3 polynomial.
const POLYNOMIAL: u32 = 0xEDB8_8320;

/// CRC-32 of `bytes` (initial value and final XOR 0xFFFF_FFFF).
///
/// `crc32(b"123456789")` is the standard check value 0xCBF4_3926.
pub fn crc32(bytes: &[u8]) -> u32 {
    !bytes.iter().fold(!0_u32, |crc, &byte| {
        (0..8).fold(crc ^ u32::from(byte), |crc, _| {
            // All ones when the low bit is set, else zero: a branch-free conditional XOR.
            let mask = (crc & 1).wrapping_neg();
            (crc >> 1) ^ (POLYNOMIAL & mask)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::crc32;

    #[test]
    fn matches_the_standard_check_values() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b""), 0);
        assert_eq!(
            crc32(b"The quick brown fox jumps over the lazy dog"),
            0x414F_A339
        );
    }
}
