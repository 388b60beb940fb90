//! A value parser that knows the values it accepts: the option's own parser (so errors are
//! unchanged) plus the list help and the completion scripts take from it, for options whose
//! values are words but also forms with a parameter (`mix:P`, `x,y`) that no `ValueEnum`
//! can spell.

use std::ffi::OsStr;

use clap::builder::{PossibleValue, TypedValueParser};
use clap::{Arg, Command};

/// Parses with `parse`; [`TypedValueParser::possible_values`] lists `words`.
#[derive(Clone)]
pub struct Listed<T> {
    parse: fn(&str) -> Result<T, String>,
    words: Vec<&'static str>,
}

/// The parser `parse` whose accepted values are `words` (forms with a parameter given by
/// their pattern, e.g. `mix:P`).
pub fn listed<T>(
    parse: fn(&str) -> Result<T, String>,
    words: impl IntoIterator<Item = &'static str>,
) -> Listed<T> {
    Listed {
        parse,
        words: words.into_iter().collect(),
    }
}

impl<T: Clone + Send + Sync + 'static> TypedValueParser for Listed<T> {
    type Value = T;

    fn parse_ref(&self, cmd: &Command, arg: Option<&Arg>, value: &OsStr) -> Result<T, clap::Error> {
        self.parse.parse_ref(cmd, arg, value)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.words.iter().copied().map(PossibleValue::new)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_yes(s: &str) -> Result<bool, String> {
        (s == "yes")
            .then_some(true)
            .ok_or(format!("'{s}' is not yes"))
    }

    #[test]
    fn parses_with_the_function_and_lists_the_words() {
        let parser = listed(parse_yes, ["yes", "y:P"]);
        let cmd = Command::new("t");
        assert!(parser.parse_ref(&cmd, None, OsStr::new("yes")).unwrap());
        let error = parser.parse_ref(&cmd, None, OsStr::new("no")).unwrap_err();
        assert!(error.to_string().contains("'no' is not yes"), "{error}");
        let words: Vec<String> = parser
            .possible_values()
            .unwrap()
            .map(|v| v.get_name().to_string())
            .collect();
        assert_eq!(words, ["yes", "y:P"]);
    }
}
