//! Where an offset of a text is, and how much of an input a message quotes: the one rule for
//! line numbers (LF, CRLF and old-Mac CR files alike) and for excerpts of input in messages
//! (a quoted line or list stays short however long the input is).

/// The most characters of an input line a message quotes \[characters\].
pub const MAX_QUOTED_CHARS: usize = 80;

/// 1-based line numbers of byte offsets, counted incrementally: a pass asking for increasing
/// offsets reads the text once in all. A line ends at LF, at CRLF (one line end) and at a CR
/// not followed by LF (old-Mac files), as XML reads them.
pub struct LineCounter<'a> {
    bytes: &'a [u8],
    /// Byte offset up to which line ends have been counted.
    position: usize,
    /// Line of `position`.
    line: usize,
}

impl<'a> LineCounter<'a> {
    pub fn new(text: &'a str) -> Self {
        Self {
            bytes: text.as_bytes(),
            position: 0,
            line: 1,
        }
    }

    /// The line (from 1) of byte `offset` (clamped to the text's end).
    pub fn line_at(&mut self, offset: usize) -> usize {
        let offset = offset.min(self.bytes.len());
        if offset < self.position {
            self.position = 0;
            self.line = 1;
        }
        let bytes = self.bytes;
        let ends = (self.position..offset)
            .filter(|&i| match bytes[i] {
                b'\n' => true,
                // A CR ends a line unless an LF follows (CRLF counts once, at its LF).
                b'\r' => bytes.get(i + 1) != Some(&b'\n'),
                _ => false,
            })
            .count();
        self.line += ends;
        self.position = offset;
        self.line
    }
}

/// The line (from 1) and column (from 1, in characters) of byte `offset` of `text`, and that
/// line's text without its line end; line ends as [`LineCounter`] counts them.
pub fn line_and_column(text: &str, offset: usize) -> (usize, usize, &str) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let line = LineCounter::new(text).line_at(offset);
    let start = text[..offset].rfind(['\n', '\r']).map_or(0, |i| i + 1);
    let end = text[offset..]
        .find(['\n', '\r'])
        .map_or(text.len(), |i| offset + i);
    let column = text[start..offset].chars().count() + 1;
    (line, column, &text[start..end])
}

/// `text` whole if it has at most `max_chars` characters, else its first `max_chars` and how
/// many there are (`abc… (1048576 characters)`).
pub fn excerpt(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}… ({} characters)", &text[..cut], text.chars().count()),
    }
}

/// The longest word a message quotes whole \[characters\]: a longer one (a pasted value of
/// megabytes, a TOML line quoted by a parser) is cut to its start and its length.
pub const MAX_QUOTED_WORD: usize = 120;

/// `message` with every word longer than [`MAX_QUOTED_WORD`] cut to its first 60 characters
/// and a note of its length, so a bad value never floods the terminal (the CLI's errors and
/// the Python package's exceptions alike).
pub fn cut_long_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(1 << 16));
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let n = word.chars().count();
        if n > MAX_QUOTED_WORD {
            out.extend(word.chars().take(60));
            out.push_str(&format!("… ({n} characters)"));
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in message.chars() {
        if c.is_whitespace() {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// The longest message an error carries \[characters\]: what is past it is cut with a note of
/// the length (a message that lists or quotes input is already short; this bounds the rest).
pub const MAX_MESSAGE_CHARS: usize = 2000;

/// `message` as an error shows it: long words cut ([`cut_long_words`]), then at most
/// [`MAX_MESSAGE_CHARS`] characters ([`excerpt`]). The CLI's `error:` lines and the Python
/// package's exceptions both pass through it.
pub fn bounded_message(message: &str) -> String {
    excerpt(&cut_long_words(message), MAX_MESSAGE_CHARS)
}

/// The first `n` of `names` joined by commas, and how many more there are (`a, b, c and 12
/// more`): a list in a message stays short however long it is.
pub fn first_few<S: AsRef<str>>(names: &[S], n: usize) -> String {
    let shown: Vec<&str> = names.iter().take(n).map(AsRef::as_ref).collect();
    match names.len().saturating_sub(n) {
        0 => shown.join(", "),
        more => format!("{} and {more} more", shown.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_is_bounded_word_by_word_and_whole() {
        let word = "x".repeat(1 << 20);
        let cut = bounded_message(&format!("bad value {word} here"));
        assert_eq!(
            cut,
            format!("bad value {}… (1048576 characters) here", "x".repeat(60))
        );
        let many = "ab ".repeat(100_000);
        let cut = bounded_message(&many);
        assert!(
            cut.ends_with("… (300000 characters)"),
            "{}",
            &cut[cut.len() - 40..]
        );
        assert!(cut.chars().count() < MAX_MESSAGE_CHARS + 40);
        assert_eq!(bounded_message("short: fine"), "short: fine");
    }

    #[test]
    fn lines_end_at_lf_crlf_and_cr_alike() {
        for end in ["\n", "\r\n", "\r"] {
            let text = ["a", "bb", "", "ccc = x"].join(end);
            let at = text.find('x').unwrap();
            assert_eq!(line_and_column(&text, at), (4, 7, "ccc = x"), "{end:?}");
            let mut lines = LineCounter::new(&text);
            assert_eq!(lines.line_at(0), 1, "{end:?}");
            assert_eq!(lines.line_at(text.find('b').unwrap()), 2, "{end:?}");
            assert_eq!(lines.line_at(at), 4, "{end:?}");
            assert_eq!(lines.line_at(text.len()), 4, "{end:?}");
        }
        // A CRLF split by the offset is still one line end.
        assert_eq!(LineCounter::new("a\r\nb").line_at(2), 1);
        assert_eq!(LineCounter::new("a\r\nb").line_at(3), 2);
    }

    #[test]
    fn excerpts_and_lists_stay_short() {
        assert_eq!(excerpt("short", 80), "short");
        let long = "é".repeat(1 << 20);
        let cut = excerpt(&long, 80);
        assert!(
            cut.ends_with("… (1048576 characters)") && cut.chars().count() < 110,
            "{cut}"
        );
        let names: Vec<String> = (0..20000).map(|i| format!("link{i}")).collect();
        assert_eq!(first_few(&names, 3), "link0, link1, link2 and 19997 more");
        assert_eq!(first_few(&names[..2], 3), "link0, link1");
    }
}
