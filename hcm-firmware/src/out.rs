//! Lines to the host's stdout over semihosting, without `core::fmt` (which would cost
//! kilobytes of flash): words, unsigned decimals and raw hex bit patterns.

use cortex_m_semihosting::hio::{self, HostStream};

/// Longest line held before it is written (longer lines are written in pieces).
const CAPACITY: usize = 160;

/// One line being assembled; [`Line::end`] writes it with its newline.
pub struct Line {
    stream: Option<HostStream>,
    buffer: [u8; CAPACITY],
    len: usize,
}

impl Line {
    /// An empty line on the host's stdout (printing nothing if the host has none).
    pub fn new() -> Self {
        Line {
            stream: hio::hstdout().ok(),
            buffer: [0; CAPACITY],
            len: 0,
        }
    }

    /// Appends `text`.
    pub fn word(&mut self, text: &str) -> &mut Self {
        for &byte in text.as_bytes() {
            self.byte(byte);
        }
        self
    }

    /// Appends a space and `value` in decimal.
    pub fn decimal(&mut self, value: u32) -> &mut Self {
        let mut digits = [0_u8; 10];
        let mut n = value;
        let mut count = 0;
        loop {
            digits[count] = b'0' + (n % 10) as u8;
            count += 1;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        self.byte(b' ');
        for &digit in digits[..count].iter().rev() {
            self.byte(digit);
        }
        self
    }

    /// Appends a space and `bits` as eight hex digits.
    pub fn hex(&mut self, bits: u32) -> &mut Self {
        const DIGITS: &[u8; 16] = b"0123456789abcdef";
        self.byte(b' ');
        for shift in (0..8).rev() {
            self.byte(DIGITS[((bits >> (4 * shift)) & 0xf) as usize]);
        }
        self
    }

    /// Writes the line and its newline, and starts a new one.
    pub fn end(&mut self) {
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
