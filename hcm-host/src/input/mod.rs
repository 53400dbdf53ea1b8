//! Files read whole — scenarios, physics files, trained residuals, blobs — with a
//! size limit, and error messages that quote at most a short excerpt of them.
//!
//! A file of a gigabyte handed to `--scenario` by mistake must be refused from its
//! size, not read; and a parser's message that echoes the offending line (TOML's
//! does) must not echo a gigabyte-long line to the terminal.

pub mod numbers;

use crate::output::bytes;
use std::io::Read;
use std::path::Path;

/// The largest text file read whole (bytes): 16 MiB, some thousand times the largest
/// scenario or trained residual hcm writes.
pub const TEXT_LIMIT: u64 = 16 << 20;

/// The longest excerpt of an input quoted in a message (characters).
pub const EXCERPT: usize = 80;

/// The file at `path` as bytes, refused past `limit` bytes. `what` names the kind of
/// file in the message ("a scenario").
pub fn read_bytes(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read it: {e}"))?;
    let too_big = |size: u64| {
        format!(
            "is {} ({size} bytes); {what} is at most {}: is this the right file?",
            bytes(size),
            bytes(limit)
        )
    };
    if let Ok(metadata) = file.metadata() {
        if metadata.is_file() && metadata.len() > limit {
            return Err(too_big(metadata.len()));
        }
    }
    let mut contents = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut contents)
        .map_err(|e| format!("cannot read it: {e}"))?;
    if contents.len() as u64 > limit {
        return Err(format!(
            "holds more than {}; {what} is at most that: is this the right file?",
            bytes(limit)
        ));
    }
    Ok(contents)
}

/// The text file at `path`, refused past `limit` bytes, when it is not UTF-8 or when
/// it holds a NUL byte (a binary file), naming the line.
pub fn read_text(path: &Path, limit: u64, what: &str) -> Result<String, String> {
    let contents = read_bytes(path, limit, what)?;
    let line_of = |offset: usize| 1 + contents[..offset].iter().filter(|&&b| b == b'\n').count();
    if let Some(offset) = contents.iter().position(|&b| b == 0) {
        return Err(format!(
            "line {}: a NUL byte (byte {offset}): {what} is a text file, this one is binary",
            line_of(offset)
        ));
    }
    String::from_utf8(contents.clone()).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        format!(
            "line {}: not UTF-8 text (byte {offset}); {what} is UTF-8 text",
            line_of(offset)
        )
    })
}

/// `message` cut to at most [`EXCERPT`] × 4 characters (parsers quote the values
/// they refuse; a value can be a megabyte long).
pub fn shorten(message: &str) -> String {
    cut(message, 4 * EXCERPT)
}

/// `message` cut to at most [`EXCERPT`] × 16 characters: for a parser's message that
/// quotes a few lines of the input under its own caret (TOML's), which [`shorten`]
/// would cut before the reason.
pub fn bounded(message: &str) -> String {
    cut(message, 16 * EXCERPT)
}

/// A TOML error in `text` as a message: TOML's own (the line, a caret under the
/// span, the reason) when the line is short, otherwise the line and column with at
/// most [`EXCERPT`] characters of the line around the error.
pub fn toml_error(text: &str, error: &toml::de::Error) -> String {
    let Some(span) = error.span() else {
        return shorten(error.message());
    };
    let start = floor_boundary(text, span.start.min(text.len()));
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = &text[line_start..line_end];
    let own = error.to_string();
    // TOML's own message quotes the line (or lines) of the span: kept while short.
    if line.chars().count() <= 4 * EXCERPT && own.len() <= 8 * EXCERPT {
        return own;
    }
    let number = 1 + text[..line_start].matches('\n').count();
    let column = 1 + text[line_start..start].chars().count();
    // Half the excerpt before the error, half from it on.
    let before = text[line_start..start]
        .char_indices()
        .rev()
        .nth(EXCERPT / 2 - 1)
        .map_or(line_start, |(i, _)| line_start + i);
    let near = excerpt(&text[before..line_end]);
    format!(
        "TOML parse error at line {number}, column {column} (near `{near}`): {}",
        shorten(error.message())
    )
}

/// A JSON error in `text` as a message: an empty or cut-off file said as such, with
/// `remedy` (how to write the file again); otherwise the line, column and reason.
pub fn json_error(text: &str, error: &serde_json::Error, remedy: &str) -> String {
    if text.trim().is_empty() {
        return format!("the file is empty; {remedy}");
    }
    if error.is_eof() {
        return format!(
            "the file ends at line {} before its JSON does: it was cut short (an \
             interrupted copy or write?); {remedy}",
            text.lines().count()
        );
    }
    shorten(&error.to_string())
}

/// The first characters of `text` (at most [`EXCERPT`]), control characters escaped.
pub fn excerpt(text: &str) -> String {
    cut(&text.escape_debug().to_string(), EXCERPT)
}

/// `text` cut to at most `most` characters, "…" marking the cut.
fn cut(text: &str, most: usize) -> String {
    match text.char_indices().nth(most) {
        None => text.to_owned(),
        Some((index, _)) => format!("{}… ({} bytes in all)", &text[..index], text.len()),
    }
}

/// The largest character boundary of `text` at or before `index`.
fn floor_boundary(text: &str, mut index: usize) -> usize {
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_past_the_limit_is_refused_from_its_size() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.toml");
        std::fs::write(&path, vec![b'a'; 2_000]).unwrap();
        let err = read_text(&path, 1_000, "a scenario").unwrap_err();
        assert!(
            err.contains("is 2.0 kB (2000 bytes); a scenario is at most 1.0 kB"),
            "{err}"
        );
        assert_eq!(read_text(&path, 2_000, "a scenario").unwrap().len(), 2_000);
    }

    #[test]
    fn nul_bytes_and_non_utf8_are_refused_naming_the_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.toml");
        std::fs::write(&path, b"a = 1\nb = \0\n").unwrap();
        let err = read_text(&path, TEXT_LIMIT, "a scenario").unwrap_err();
        assert!(err.starts_with("line 2: a NUL byte (byte 10)"), "{err}");
        std::fs::write(&path, b"a = 1\n\nb = \xff\n").unwrap();
        let err = read_text(&path, TEXT_LIMIT, "a scenario").unwrap_err();
        assert!(err.starts_with("line 3: not UTF-8 text (byte 11)"), "{err}");
    }

    #[test]
    fn a_long_line_is_quoted_as_a_short_excerpt() {
        let text = format!("name = \"x\"\nvalue = [{}\n", "1, ".repeat(100_000));
        let error = toml::from_str::<toml::Table>(&text).unwrap_err();
        let message = toml_error(&text, &error);
        assert!(message.len() < 1_000, "{} bytes", message.len());
        assert!(
            message.starts_with("TOML parse error at line 2, column"),
            "{message}"
        );
        // A short line keeps TOML's own message, caret and all.
        let error = toml::from_str::<toml::Table>("a = [1,\n").unwrap_err();
        assert_eq!(toml_error("a = [1,\n", &error), error.to_string());
    }

    #[test]
    fn an_empty_or_cut_json_file_is_said_to_be_so() {
        let message = |text: &str| {
            let error = serde_json::from_str::<serde_json::Value>(text).unwrap_err();
            json_error(text, &error, "write it again")
        };
        assert_eq!(message(" \n"), "the file is empty; write it again");
        let cut = message("{\n  \"a\": [1,\n 2");
        assert!(
            cut.starts_with("the file ends at line 3 before its JSON does"),
            "{cut}"
        );
        assert!(message("{\"a\": x}").contains("line 1 column 7"));
    }
}
