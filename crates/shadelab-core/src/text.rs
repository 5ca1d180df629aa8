//! Text from files and arguments made safe to show in a message.
//!
//! Anything a message repeats from outside (a token of a model file, a
//! material name, a file name, a command-line value) may hold terminal
//! escape sequences, bidirectional overrides or megabytes of text. Every
//! message that repeats such a token passes it through [`escape_token`]:
//! control and invisible formatting characters are written as Rust-style
//! escapes (`\n`, `\t`, `\r`, `\u{1b}`), and the token is cut to
//! [`MAX_ECHOED_CHARS`] characters, saying how long it was. The command line
//! also passes every whole message through [`escape_message`] before
//! printing it, so a message built by a library (a TOML parser's excerpt of
//! the offending line) is made safe too.

use crate::limits::{MAX_ECHOED_CHARS, MAX_MESSAGE_LINE_CHARS};

/// `token` as a message may show it: control characters escaped, at most
/// [`MAX_ECHOED_CHARS`] characters of it kept.
pub fn escape_token(token: &str) -> String {
    escape_capped(token, MAX_ECHOED_CHARS, false)
}

/// A whole message as a terminal may show it: each line escaped as
/// [`escape_token`] does (line breaks are kept) and cut to
/// [`MAX_MESSAGE_LINE_CHARS`] characters.
pub fn escape_message(message: &str) -> String {
    escape_capped(message, MAX_MESSAGE_LINE_CHARS, true)
}

/// `v` as a message shows a number the user gave: as `{}` prints it for
/// ordinary magnitudes (`0.25`, `180`), and in the shortest exponent form
/// for very large or small ones (`1e-30`, `3.4028235e38`), which `{}`
/// would print as dozens of digits.
pub fn format_number(v: f32) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() || (1e-4..1e16).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Whether `c` must not reach a terminal as it is: C0 and C1 controls, DEL,
/// and the invisible characters that reorder or hide text (bidirectional
/// embeddings, overrides and isolates, zero-width characters, the BOM).
pub fn is_unsafe_char(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{200b}'..='\u{200f}'
                | '\u{202a}'..='\u{202e}'
                | '\u{2060}'..='\u{2069}'
                | '\u{feff}'
        )
}

/// The shared work: escape, keep `\n` as a line break when `lines`, and cut
/// each line (or the whole, when not `lines`) after `max_chars` characters.
fn escape_capped(text: &str, max_chars: usize, lines: bool) -> String {
    let mut out = String::with_capacity(text.len().min(4 * max_chars + 32));
    let mut pieces = if lines {
        text.split('\n').collect::<Vec<_>>()
    } else {
        vec![text]
    };
    let last = pieces.len() - 1;
    for (k, piece) in pieces.drain(..).enumerate() {
        for (kept, (at, c)) in piece.char_indices().enumerate() {
            if kept == max_chars {
                let more = piece[at..].chars().count();
                let plural = if more == 1 { "" } else { "s" };
                out.push_str(&format!("… ({more} more character{plural})"));
                break;
            }
            match c {
                '\n' => out.push_str("\\n"),
                '\r' => out.push_str("\\r"),
                '\t' => out.push_str("\\t"),
                c if is_unsafe_char(c) => out.push_str(&format!("\\u{{{:x}}}", c as u32)),
                c => out.push(c),
            }
        }
        if k != last {
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_are_escaped_and_long_tokens_cut() {
        assert_eq!(escape_token("plain näme"), "plain näme");
        assert_eq!(
            escape_token("\u{1b}[31mred\u{7}\r\n\t\u{202e}"),
            "\\u{1b}[31mred\\u{7}\\r\\n\\t\\u{202e}"
        );
        let long = "x".repeat(MAX_ECHOED_CHARS + 10);
        let shown = escape_token(&long);
        assert!(shown.starts_with(&"x".repeat(MAX_ECHOED_CHARS)));
        assert!(shown.ends_with("… (10 more characters)"), "{shown}");
    }

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(format_number(179.0), "179");
        assert_eq!(format_number(0.25), "0.25");
        assert_eq!(format_number(1e-30), "1e-30");
        assert_eq!(format_number(-1e30), "-1e30");
        assert_eq!(format_number(f32::MAX), "3.4028235e38");
    }

    #[test]
    fn messages_keep_their_lines() {
        assert_eq!(escape_message("a\u{1b}\nb\r"), "a\\u{1b}\nb\\r");
        let long = format!("{}\nshort", "y".repeat(MAX_MESSAGE_LINE_CHARS + 1));
        let shown = escape_message(&long);
        assert!(shown.ends_with("… (1 more character)\nshort"), "{shown}");
    }
}
