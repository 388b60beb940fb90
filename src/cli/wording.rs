//! The library's messages in the command line's words ([`Flags`]): an option is its flag
//! (`--line-length`), a setting the flag and its value (`--line-length 0.3`, a flag alone for
//! one turned on: `--posts`), settings given together side by side.

use crate::wording::{Message, Opt, Value, Wording};

/// The command line's wording of options: `--line-length 0.3`.
pub struct Flags;

/// The command line's flag for `opt`: `--line-length` (the output file's `-o`, as messages
/// have always said it).
pub fn flag(opt: Opt) -> &'static str {
    match opt {
        Opt::Algo => "--algo",
        Opt::Api => "--api",
        Opt::Bias => "--bias",
        Opt::Braid => "--braid",
        Opt::CellSize => "--cell-size",
        Opt::Draw => "--draw",
        Opt::End => "--end",
        Opt::Floor => "--floor",
        Opt::FloorSize => "--floor-size",
        Opt::Format => "--format",
        Opt::Growing => "--growing",
        Opt::LineLength => "--line-length",
        Opt::LineWidth => "--line-width",
        Opt::LineZ => "--line-z",
        Opt::MarkerZ => "--marker-z",
        Opt::Origin => "--origin",
        Opt::Openings => "--openings",
        Opt::Output => "-o",
        Opt::OutDir => "--out-dir",
        Opt::Parent => "--parent",
        Opt::Posts => "--posts",
        Opt::PostSize => "--post-size",
        Opt::PxPerM => "--px-per-m",
        Opt::ResizeFloor => "--resize-floor",
        Opt::Rotation => "--rotation",
        Opt::Size => "--size",
        Opt::Start => "--start",
        Opt::WallHeight => "--wall-height",
        Opt::WallLength => "--wall-length",
        Opt::WallThickness => "--wall-thickness",
        Opt::Width => "--width",
    }
}

impl Wording for Flags {
    fn option(&self, opt: Opt) -> String {
        flag(opt).to_string()
    }

    fn setting(&self, opt: Opt, value: &Value) -> String {
        match value {
            Value::Number(v) | Value::Word(v) => format!("{} {v}", flag(opt)),
            Value::Placeholder(v) => format!("{} {v}", flag(opt)),
            Value::On => flag(opt).to_string(),
        }
    }

    fn separator(&self) -> &str {
        " "
    }

    fn generate(&self, settings: &str) -> String {
        format!("vrep-maze generate {settings}")
    }
}

/// `message` in the command line's words.
pub fn worded(message: &Message) -> String {
    message.worded(&Flags)
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn a_library_refusal_reads_as_flags_in_the_error_line() {
        use crate::layout::endpoints::{Corner, EndpointSpec};
        use crate::layout::{GenerateSpec, build_layout};
        let mut spec = GenerateSpec::course(
            crate::maze::Grid::new(9, 9).unwrap(),
            crate::generate::Algorithm::Dfs,
            1,
        );
        spec.start = EndpointSpec::FarthestPair;
        spec.end = EndpointSpec::Corner(Corner::NorthEast);
        let refused = build_layout(&spec).unwrap_err();
        let line =
            "--end ne conflicts with --start farthest-pair, which picks both ends: drop --end";
        assert_eq!(worded(&refused), line);
        // as a usage error, and as a cause of another error: the line the command prints
        assert_eq!(
            crate::cli::usage::one_line(&crate::cli::usage::usage(refused.clone())),
            line
        );
        let caused = anyhow::Error::new(refused).context("making the maze");
        assert_eq!(
            crate::cli::usage::one_line(&caused),
            format!("making the maze: {line}")
        );
    }

    #[test]
    fn every_flag_is_an_option_of_some_command() {
        let cli = crate::cli::Cli::command();
        let known = |flag: &str| {
            cli.get_subcommands()
                .flat_map(|s| s.get_arguments())
                .chain(cli.get_arguments())
                .any(|a| match flag.strip_prefix("--") {
                    Some(long) => a.get_long() == Some(long),
                    None => a.get_short().map(|c| format!("-{c}")).as_deref() == Some(flag),
                })
        };
        for opt in Opt::ALL {
            assert!(known(flag(opt)), "{opt:?}: {} is no option", flag(opt));
        }
    }
}
