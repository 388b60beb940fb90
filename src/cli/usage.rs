//! Usage errors and error lines: a command line that asks for something impossible
//! ([`UsageError`], made by `usage` and `ensure_usage!`; clap's own errors in `report_usage`) and
//! any error said as the command line says it: one line ([`one_line`]), the details an
//! invalid layout lists ([`details`]) and the remedies as hints ([`hints`]). Programs that
//! embed the command line (the Python package) word them with [`one_line_with`],
//! [`details_with`] and [`cause_hints`].

use std::ffi::OsString;
use std::process::ExitCode;

use clap::Parser;

use super::escape;
use super::hinted::{ConnectError, Hinted};
use super::remedies;
use super::stdout;
use super::wording;

/// Exit code of a command line that asks for something impossible (clap uses it too).
pub(crate) const USAGE_EXIT_CODE: u8 = 2;

/// A command line that asks for something impossible (a value out of range, options that
/// conflict): reported like clap's own usage errors, with exit code 2. Any other failure
/// exits with 1. Public so that programs embedding the command line (the Python package)
/// tell usage errors from failures as the exit code does.
/// Its message is the command line's text, or a library's message naming options, which
/// [`wording::Flags`] words (an embedding program words it its own way).
#[derive(Debug, thiserror::Error)]
#[error("{}", wording::worded(.0))]
pub struct UsageError(pub crate::wording::Message);

/// `message` as a [`UsageError`].
pub(crate) fn usage(message: impl Into<crate::wording::Message>) -> anyhow::Error {
    anyhow::Error::new(UsageError(message.into()))
}

/// Fails with a [`UsageError`] unless `condition` holds.
macro_rules! ensure_usage {
    ($condition:expr, $($message:tt)+) => {
        if !$condition {
            return Err(anyhow::Error::new($crate::cli::usage::UsageError(format!($($message)+).into())));
        }
    };
}
pub(crate) use ensure_usage;

/// Help and version go to standard output as clap prints them (a write error is one
/// `error:` line and exit code 1, a closed pipe exit 0); a usage error becomes one `error:`
/// line (clap's first), its tips `hint:` lines, and exit code 2. The command line's
/// arguments (`args`) that clap echoes are shown with their control characters escaped
/// (parsed again as `C`, the command line that failed).
pub(crate) fn report_usage<C: Parser>(error: &clap::Error, args: &[OsString]) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let printed = if error.use_stderr() {
            error.print().map_err(anyhow::Error::new)
        } else {
            stdout::write_stdout(|_| error.print())
        };
        match printed {
            Ok(()) => {}
            Err(e) if e.is::<stdout::PipeClosed>() => return ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {}", one_line(&e));
                return ExitCode::FAILURE;
            }
        }
        return if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(USAGE_EXIT_CODE)
        } else {
            ExitCode::SUCCESS
        };
    }
    let text = rendered_escaped::<C>(error, args);
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    if let Some(first) = lines.next() {
        eprintln!("{}{}", shorten(first), missing_arguments(error));
    }
    // clap's tips, and the values an option takes when the one given is not among them
    for line in lines {
        if let Some(tip) = line.strip_prefix("tip:") {
            eprintln!("  hint:{}", shorten(tip));
        } else if let Some(values) = line.strip_prefix("[possible values: ") {
            eprintln!("  hint: one of {}", shorten(values.trim_end_matches(']')));
        }
    }
    eprintln!("  hint: `--help` lists every option, with examples");
    ExitCode::from(USAGE_EXIT_CODE)
}

/// clap's text for `error`, the failure of the command line `args` (program name first) as
/// `C` parses it, with the arguments it echoes shown as escapes (`cli::escape`):
/// clap echoes them with their control characters, or drops some (`\0`, an escape
/// sequence), so the same command line with them escaped is parsed again, which fails the
/// same way and echoes the escapes. The one reader of clap's errors for the command line
/// and for a program that embeds it (the Python package).
pub fn rendered_escaped<C: Parser>(error: &clap::Error, args: &[OsString]) -> String {
    let escaped: Vec<String> = args
        .iter()
        .map(|arg| escape::escaped(&arg.to_string_lossy()).into_owned())
        .collect();
    let again = C::try_parse_from(&escaped)
        .err()
        .filter(|again| again.kind() == error.kind());
    again.as_ref().unwrap_or(error).render().to_string()
}

/// The arguments a `MissingRequiredArgument` error names (" <FILE>, --seeds <SEEDS>"), to
/// follow clap's first line ("... were not provided:"), which names none; empty otherwise.
fn missing_arguments(error: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if error.kind() != ErrorKind::MissingRequiredArgument {
        return String::new();
    }
    match error.get(ContextKind::InvalidArg) {
        Some(ContextValue::Strings(names)) => format!(" {}", names.join(", ")),
        Some(ContextValue::String(name)) => format!(" {name}"),
        _ => String::new(),
    }
}

/// Longest text of one cause in an error line; longer ones (e.g. an echoed 100 KB argument)
/// are cut, saying how long they were.
const MAX_CAUSE_CHARS: usize = 400;

/// The error and its causes on one line, each cause once: a cause whose text the line
/// already holds (an inner error that its context also printed) is not repeated.
pub fn one_line(error: &anyhow::Error) -> String {
    one_line_with(error, cause_text)
}

/// [`one_line`] with each cause's text from `text`: a program that embeds the command line
/// (the Python package) says the drawing errors in its own words.
pub fn one_line_with(
    error: &anyhow::Error,
    text: impl Fn(&(dyn std::error::Error + 'static)) -> String,
) -> String {
    let mut line = String::new();
    for cause in error.chain() {
        let text = shorten(&escape::escaped(&text(cause)));
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// `text`, or its start and a note of its length when it is longer than [`MAX_CAUSE_CHARS`].
pub(crate) fn shorten(text: &str) -> String {
    let chars = text.chars().count();
    if chars <= MAX_CAUSE_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_CAUSE_CHARS).collect();
    format!("{head}... ({chars} characters in all)")
}

/// What the error's causes list beyond their one line (an invalid layout's problems).
pub fn details(error: &anyhow::Error) -> Vec<String> {
    details_with(error, &wording::Flags)
}

/// [`details`] with the options the problems name in `wording`'s words: a program that
/// embeds the command line (the Python package) says them in its own.
pub fn details_with(error: &anyhow::Error, wording: &dyn crate::wording::Wording) -> Vec<String> {
    error
        .chain()
        .filter_map(|cause| cause.downcast_ref::<crate::validate::Invalid>())
        .flat_map(|invalid| invalid.shown(wording))
        .map(|line| shorten(&escape::escaped(&line)))
        .collect()
}

/// A failed export as its own cause, so the invalid layout's problems ([`details`]) and a
/// refusal's options ([`one_line`]) are found in the chain and worded by the command line,
/// or by a program that embeds it.
pub fn export_error(error: crate::export::ExportError) -> anyhow::Error {
    use crate::export::ExportError;
    match error {
        ExportError::Invalid(e) => anyhow::Error::new(e),
        ExportError::BlockGrid(e) => anyhow::Error::new(e),
        ExportError::Refused(e) => anyhow::Error::new(e),
        ExportError::Io(e) => anyhow::Error::new(e),
    }
}

/// One cause's text in the command line's words: a drawing error's roles with their options
/// ([`remedies::message`]), a library message's options as flags ([`wording::Flags`]), any
/// other cause as it displays itself.
fn cause_text(cause: &(dyn std::error::Error + 'static)) -> String {
    if let Some(draw) = cause.downcast_ref::<crate::draw::DrawError>() {
        return remedies::message(draw);
    }
    match cause.downcast_ref::<crate::wording::Message>() {
        Some(message) => wording::worded(message),
        None => cause.to_string(),
    }
}

/// The remedies the error's causes know of, one per line, printed after the error line.
pub fn hints(error: &anyhow::Error) -> Vec<String> {
    error.chain().flat_map(cause_hints).collect()
}

/// The remedies one cause knows of, in the command line's words (a drawing error's from
/// [`remedies::hints`]).
pub fn cause_hints(cause: &(dyn std::error::Error + 'static)) -> Vec<String> {
    let draw = cause.downcast_ref::<crate::draw::DrawError>();
    let connect = cause.downcast_ref::<ConnectError>();
    let hinted = cause.downcast_ref::<Hinted>();
    let invalid = cause.downcast_ref::<crate::validate::Invalid>();
    draw.map(remedies::hints)
        .into_iter()
        .chain(connect.map(|e| e.hints()))
        .chain(hinted.map(|e| e.hints()))
        .chain(
            invalid
                .and_then(super::validate::metrics_hint)
                .map(|h| vec![h]),
        )
        .flatten()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::{DrawError, Role};

    #[test]
    fn a_cause_that_its_context_already_printed_is_not_repeated() {
        let os = std::io::Error::new(std::io::ErrorKind::NotFound, "No such file (os error 2)");
        let error = anyhow::Error::new(os).context("m.json: No such file (os error 2)");
        let line = one_line(&error);
        assert_eq!(line.matches("No such file").count(), 1, "{line}");
        let error = anyhow::anyhow!("inner").context("outer");
        assert_eq!(one_line(&error), "outer: inner");
    }

    #[test]
    fn a_refused_value_is_echoed_with_its_control_characters_escaped_not_dropped() {
        for (value, shown) in [
            ("dfs\0x", "'dfs\\0x'"),
            ("\u{1b}[31m", "'\\u{1b}[31m'"),
            ("a\nerror: forged", "'a\\nerror: forged'"),
        ] {
            let args: Vec<OsString> = ["vrep-maze", "generate", "--algo"]
                .into_iter()
                .map(OsString::from)
                .chain([OsString::from(value)])
                .collect();
            let error = crate::cli::Cli::try_parse_from(&args).unwrap_err();
            let text = rendered_escaped::<crate::cli::Cli>(&error, &args);
            let first = text.lines().next().unwrap();
            assert!(
                first.contains(&format!("invalid value {shown} for '--algo <ALGO>'"))
                    && first.contains(&format!("unknown algorithm {shown}")),
                "{first:?}"
            );
            assert!(
                !text.chars().any(|c| c.is_control() && c != '\n'),
                "{text:?}"
            );
        }
    }

    #[test]
    fn a_huge_cause_is_cut_and_says_its_length() {
        let error = anyhow::anyhow!("{}", "x".repeat(100_000)).context("no object `...`");
        let line = one_line(&error);
        assert!(line.len() < 1000, "{} bytes", line.len());
        assert!(line.contains("100000 characters in all"), "{line}");
    }

    #[test]
    fn remedies_are_hints_on_their_own_lines_not_in_the_error_line() {
        let error = anyhow::Error::new(DrawError::Missing {
            objects: vec![(Role::Floor, "Floor".into()), (Role::Line, "Line".into())],
            sizes: None,
        })
        .context("drawing m.json");
        assert_eq!(
            one_line(&error),
            "drawing m.json: missing in the scene: Floor, Line"
        );
        let hints = hints(&error);
        assert_eq!(hints.len(), 3, "{hints:?}");
        assert!(hints[0].contains("--floor"), "{hints:?}");
        assert!(hints.iter().all(|h| !h.contains('\n')), "{hints:?}");
        let running = anyhow::Error::new(DrawError::SimulationRunning);
        assert!(super::hints(&running)[0].contains("--stop-simulation"));
    }
}
