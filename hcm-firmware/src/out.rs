//! Lines to the host's stdout over semihosting, without `core::fmt` (which would cost
//! kilobytes of flash): words, then unsigned numbers in decimal or as raw hex bit
//! patterns.
//!
//! One function writes every line ([`Out::line`], never inlined): its callers pass
//! the line's words and numbers as slices. Built up word by word at each call site
//! instead, every caller held its own copy of the writing: this way the ball image
//! takes 748 B less flash and a peg image 296 B less.

use cortex_m_semihosting::hio::{self, HostStream};

/// Longest run of bytes held before it is written (longer lines go in pieces).
const CAPACITY: usize = 160;

/// How a line's numbers are written.
#[derive(Clone, Copy)]
pub enum Radix {
    /// Unsigned decimal, no leading zeros.
    Decimal,
    /// Eight hex digits: a raw 32-bit pattern.
    Hex,
}

/// The host's stdout and the line being written.
pub struct Out {
    stream: Option<HostStream>,
    buffer: [u8; CAPACITY],
    len: usize,
}

impl Out {
    /// The host's stdout (printing nothing if the host has none).
    pub fn new() -> Self {
        Out {
            stream: hio::hstdout().ok(),
            buffer: [0; CAPACITY],
            len: 0,
        }
    }

    /// `case GROUP.ITEM HEX…`: a table's result as raw bit patterns.
    #[inline(never)]
    pub fn case(&mut self, group: &str, item: &str, bits: &[u32]) {
        self.line(&["case ", group, ".", item], bits, Radix::Hex);
    }

    /// `cost GROUP.ITEM N`: instructions per evaluation.
    #[inline(never)]
    pub fn cost(&mut self, group: &str, item: &str, instructions: u32) {
        self.line(
            &["cost ", group, ".", item],
            &[instructions],
            Radix::Decimal,
        );
    }

    /// Writes `words` one after the other as they are, then a space and each of
    /// `numbers` in `radix`, then the newline.
    #[inline(never)]
    pub fn line(&mut self, words: &[&str], numbers: &[u32], radix: Radix) {
        for word in words {
            for &byte in word.as_bytes() {
                self.byte(byte);
            }
        }
        let (base, width) = match radix {
            Radix::Decimal => (10, 1),
            Radix::Hex => (16, 8),
        };
        for &number in numbers {
            // Least significant digit first; at least `width` of them (a u32 has at
            // most 10 decimal or 8 hex digits).
            let mut digits = [b'0'; 10];
            let mut rest = number;
            let mut count = 0;
            for digit in &mut digits {
                if count >= width && rest == 0 {
                    break;
                }
                *digit = b"0123456789abcdef"[(rest % base) as usize];
                rest /= base;
                count += 1;
            }
            self.byte(b' ');
            for &digit in digits[..count].iter().rev() {
                self.byte(digit);
            }
        }
        self.byte(b'\n');
        self.flush();
    }

    fn byte(&mut self, byte: u8) {
        if self.len == CAPACITY {
            self.flush();
        }
        self.buffer[self.len] = byte;
        self.len += 1;
    }

    fn flush(&mut self) {
        if let Some(stream) = &mut self.stream {
            // Nowhere to report a failed write to: the host test sees a short output.
            let _ = stream.write_all(&self.buffer[..self.len]);
        }
        self.len = 0;
    }
}
