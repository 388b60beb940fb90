//! The library's messages in Python's words ([`Keywords`]): an option is its keyword
//! argument (`line_length`), a setting the keyword and its value (`line_length=0.3`, a word
//! quoted, `draw="mesh"`, a flag turned on `posts=True`), settings given together separated
//! by commas, a call of `generate` `vrep_maze.generate(cell_size=0.5)`.

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
/// ([`crate::errors::python_names`]).
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
        crate::errors::python_names(text)
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
}
