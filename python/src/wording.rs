//! The library's messages in Python's words ([`Keywords`]): an option is its keyword
//! argument (`line_length`), a setting the keyword and its value (`line_length=0.3`, a word
//! quoted, `draw="mesh"`, a flag turned on `posts=True`), settings given together separated
//! by commas, a call of `generate` `vrep_maze.generate(cell_size=0.5)`; the command line's
//! own text with its options rewritten as keywords ([`python_names`]).

use vrep_maze::cli::wording::flag;
use vrep_maze::wording::{Opt, Value, Wording};

/// Python's wording of options: `line_length=0.3`.
pub struct Keywords;

/// The keyword argument for `opt`: the command line's option in snake case, as
/// `options::command_line` turns a keyword into it (the output file is `path`).
pub fn keyword(opt: Opt) -> String {
    match opt {
        Opt::Output => "path".into(),
        _ => flag(opt).trim_start_matches('-').replace('-', "_"),
    }
}

impl Wording for Keywords {
    fn option(&self, opt: Opt) -> String {
        keyword(opt)
    }

    fn setting(&self, opt: Opt, value: &Value) -> String {
        let keyword = keyword(opt);
        match value {
            Value::Number(v) => format!("{keyword}={v}"),
            Value::Word(v) => format!("{keyword}=\"{v}\""),
            Value::Placeholder(v) => format!("{keyword}={v}"),
            Value::On => format!("{keyword}=True"),
        }
    }

    fn separator(&self) -> &str {
        ", "
    }

    fn generate(&self, settings: &str) -> String {
        format!("vrep_maze.generate({settings})")
    }
}

/// [`Keywords`] for a message the command line's own code put together (a usage error):
/// its text parts are in the command line's words, their options rewritten as keywords
/// ([`python_names`]).
pub struct OverCommandLine;

impl Wording for OverCommandLine {
    fn option(&self, opt: Opt) -> String {
        Keywords.option(opt)
    }

    fn setting(&self, opt: Opt, value: &Value) -> String {
        Keywords.setting(opt, value)
    }

    fn separator(&self) -> &str {
        Keywords.separator()
    }

    fn generate(&self, settings: &str) -> String {
        Keywords.generate(settings)
    }

    fn text(&self, text: &str) -> String {
        python_names(text)
    }
}

/// `text` with the command line's option names as the keywords Python takes:
/// `invalid value 'prims' for '--algo <ALGO>'` becomes `invalid value algo='prims'`,
/// `'--size <SIZE>'` becomes `size`, and a bare `--connect-timeout` `connect_timeout`
/// (`--create-missing`, a flag, `create_missing=True`).
///
/// Only for the text that comes in the command line's words, written by the command line's
/// own code: clap's parse errors, connection failures and their hints, its usage errors. The
/// library's messages carry their options as data (`wording`), a drawing error's roles and
/// remedies too (`remedies`).
pub fn python_names(text: &str) -> String {
    let keyword = |option: &str| option.trim_start_matches("--").replace('-', "_");
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("'--") {
        let Some(len) = rest[at + 1..].find('\'') else {
            break;
        };
        let quoted = &rest[at + 1..at + 1 + len];
        let name = keyword(quoted.split_whitespace().next().unwrap_or(quoted));
        let before = &rest[..at];
        // "invalid value 'X' for '--opt <V>'" reads "invalid value opt='X'"
        match before
            .strip_suffix(" for ")
            .and_then(|b| b.rsplit_once("invalid value "))
        {
            Some((head, value)) => out.push_str(&format!("{head}invalid value {name}={value}")),
            None => {
                out.push_str(before);
                out.push_str(&name);
            }
        }
        rest = &rest[at + 1 + len + 1..];
    }
    out.push_str(rest);
    bare_options(&out)
}

/// Bare `--option` words as Python keyword arguments: `option=True` for a flag,
/// `option=VALUE` with the value that follows (`--api legacy --connect-timeout 75` reads
/// `api="legacy", connect_timeout=75`), `option` alone when no value follows.
fn bare_options(text: &str) -> String {
    use clap::CommandFactory;
    let cli = vrep_maze::cli::Cli::command();
    let flag = |long: &str| {
        cli.get_subcommands()
            .flat_map(|s| s.get_arguments())
            .chain(cli.get_arguments())
            .find(|a| a.get_long() == Some(long))
            .is_some_and(|a| !a.get_action().takes_values())
    };
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    // the end of the keyword argument just written: another that follows joins with ", "
    let mut after_keyword = false;
    while let Some(at) = rest.find("--") {
        let starts_word = at == 0 || !rest[..at].ends_with(|c: char| c.is_alphanumeric());
        let name_len = rest[at + 2..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(rest.len() - at - 2);
        let long = &rest[at + 2..at + 2 + name_len];
        let between = &rest[..at];
        let keyword =
            starts_word && !long.is_empty() && long.starts_with(|c: char| c.is_ascii_alphabetic());
        if keyword && after_keyword && between == " " {
            out.push_str(", ");
        } else {
            out.push_str(between);
        }
        after_keyword = false;
        rest = &rest[at + 2 + name_len..];
        if !keyword {
            out.push_str("--");
            out.push_str(long);
            continue;
        }
        out.push_str(&long.replace('-', "_"));
        if flag(long) {
            out.push_str("=True");
            after_keyword = true;
        } else if let Some((value, left)) = option_value(rest) {
            out.push('=');
            out.push_str(&python_value(value));
            rest = left;
            after_keyword = true;
        }
    }
    out.push_str(rest);
    out
}

/// The value word that follows an option in `rest` (` 75`, ` legacy,`), without trailing
/// punctuation, and what follows it; `None` when no value follows (an option named alone).
fn option_value(rest: &str) -> Option<(&str, &str)> {
    let word_start = rest.strip_prefix(' ')?;
    let len = word_start
        .find(char::is_whitespace)
        .unwrap_or(word_start.len());
    let word = word_start[..len].trim_end_matches([',', ';', ')', ':']);
    let plain = |c: char| c.is_ascii_alphanumeric() || "._-/".contains(c);
    if word.is_empty() || word.starts_with("--") || !word.chars().all(plain) {
        return None;
    }
    // an English word after an option name ("--port: CoppeliaSim ...") is no value
    let lower_word = word.chars().all(|c| c.is_ascii_lowercase());
    let values = [
        "legacy", "zmq", "auto", "both", "mesh", "copies", "stop", "end",
    ];
    if lower_word && !values.contains(&word) {
        return None;
    }
    Some((word, &word_start[word.len()..]))
}

/// `value` as Python writes it: a number or a placeholder (`NAME`) as is, a word quoted.
fn python_value(value: &str) -> String {
    let number = value.parse::<f64>().is_ok();
    let placeholder = value.chars().any(|c| c.is_ascii_uppercase())
        && !value.chars().any(|c| c.is_ascii_lowercase());
    if number || placeholder {
        value.to_string()
    } else {
        format!("\"{value}\"")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vrep_maze::wording::{Message, Setting};

    #[test]
    fn settings_read_as_keyword_arguments() {
        let m = Message::text("generate with ")
            .and_settings(vec![
                Setting {
                    opt: Opt::Posts,
                    value: Value::On,
                },
                Setting {
                    opt: Opt::PostSize,
                    value: Value::number(0.01),
                },
            ])
            .and(", not ")
            .and_setting(Opt::Draw, Value::word("mesh"))
            .and(" or ")
            .and_opt(Opt::PxPerM);
        assert_eq!(
            m.worded(&Keywords),
            "generate with posts=True, post_size=0.01, not draw=\"mesh\" or px_per_m"
        );
    }

    #[test]
    fn hints_name_keyword_arguments_with_their_values() {
        assert_eq!(
            python_names("pass --api legacy --connect-timeout 75 to wait it out"),
            "pass api=\"legacy\", connect_timeout=75 to wait it out"
        );
        assert_eq!(
            python_names(
                "the ZeroMQ remote API answers on 127.0.0.1:23000: try --api zmq --port 23000"
            ),
            "the ZeroMQ remote API answers on 127.0.0.1:23000: try api=\"zmq\", port=23000"
        );
        assert_eq!(
            python_names("pass --robot NAME with the name"),
            "pass robot=NAME with the name"
        );
        assert_eq!(
            python_names("check --port: CoppeliaSim serves"),
            "check port: CoppeliaSim serves"
        );
        assert_eq!(
            python_names("pass --create-missing to create them"),
            "pass create_missing=True to create them"
        );
    }
}
