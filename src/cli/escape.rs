//! Text from a layout, a file name or an option, made safe to print: every control
//! character is shown as an escape (`\n`, `\t`, `\u{1b}`, `\0`), so no input can forge a
//! second `error:` line, move the cursor or hide what follows.

use std::borrow::Cow;

/// `text` with each control character escaped (borrowed when there is none).
pub(crate) fn escaped(text: &str) -> Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\0' => out.push_str("\\0"),
            c if c.is_control() => out.push_str(&format!("\\u{{{:x}}}", u32::from(c))),
            c => out.push(c),
        }
    }
    Cow::Owned(out)
}

/// `text` as one word of a POSIX shell command line, for a hint that shows a command: as
/// it is when every character is one no shell treats specially, else in single quotes (an
/// inner `'` as `'\''`).
pub(crate) fn shell_word(text: &str) -> Cow<'_, str> {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-./:=,+@%".contains(c);
    if !text.is_empty() && text.chars().all(plain) {
        return Cow::Borrowed(text);
    }
    Cow::Owned(format!("'{}'", text.replace('\'', "'\\''")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_word_with_spaces_or_quotes_is_quoted_for_the_shell() {
        assert_eq!(shell_word("maze.json"), "maze.json");
        assert_eq!(shell_word("my maze.json"), "'my maze.json'");
        assert_eq!(shell_word("it's"), "'it'\\''s'");
        assert_eq!(shell_word(""), "''");
        assert_eq!(shell_word("$(rm)"), "'$(rm)'");
    }

    #[test]
    fn control_characters_are_escaped_and_the_rest_is_kept() {
        assert!(matches!(escaped("prim é"), Cow::Borrowed("prim é")));
        assert_eq!(
            escaped("a\nerror: forged\u{1b}[2J\0\t\u{7f}\u{85}"),
            "a\\nerror: forged\\u{1b}[2J\\0\\t\\u{7f}\\u{85}"
        );
    }
}
