//! The options a library message can name, as data: the library says *which* option (an
//! [`Opt`]) and, where it matters, with which value ([`Value`]); each adapter says *how*
//! ([`Wording`]): the command line `--line-length 0.3` and `--posts`, Python `line_length=0.3`
//! and `posts=True`. A [`Message`] is a line of text, options and settings that an adapter
//! renders with [`Message::worded`]; its `Display` is a neutral fallback (`line-length=0.3`)
//! for programs that word nothing themselves.

use std::fmt;

/// An option of the command line (a keyword argument in Python) that a library message
/// names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Opt {
    /// The maze generation algorithm.
    Algo,
    /// Which remote API to draw over.
    Api,
    /// The binary tree's bias.
    Bias,
    /// The share of dead ends to braid away.
    Braid,
    /// The side of a cell.
    CellSize,
    /// How `apply` draws: copies or meshes.
    Draw,
    /// The end cell (or the end marker's name, for a drawing).
    End,
    /// The floor's name in the scene.
    Floor,
    /// The floor's size.
    FloorSize,
    /// The format of a file written.
    Format,
    /// The growing tree's mode.
    Growing,
    /// The line template's length.
    LineLength,
    /// The line template's width.
    LineWidth,
    /// The height of the lines.
    LineZ,
    /// The height of the markers.
    MarkerZ,
    /// Where cell (0, 0) lies.
    Origin,
    /// Gaps in the outer walls beside the start and end.
    Openings,
    /// The file written.
    Output,
    /// The directory a batch writes to.
    OutDir,
    /// The maze dummy's name in the scene.
    Parent,
    /// Posts at the wall corners (a flag).
    Posts,
    /// The post template's side.
    PostSize,
    /// Pixels a metre of a picture or map.
    PxPerM,
    /// Let `apply` grow the floor (a flag).
    ResizeFloor,
    /// The maze's rotation.
    Rotation,
    /// The grid's columns and rows.
    Size,
    /// The start cell (or the start marker's name, for a drawing).
    Start,
    /// The walls' height.
    WallHeight,
    /// The wall template's length.
    WallLength,
    /// The walls' thickness.
    WallThickness,
    /// A picture's width in pixels.
    Width,
}

impl Opt {
    /// Every option, for adapters to check their words against.
    pub const ALL: [Opt; 31] = [
        Opt::Algo,
        Opt::Api,
        Opt::Bias,
        Opt::Braid,
        Opt::CellSize,
        Opt::Draw,
        Opt::End,
        Opt::Floor,
        Opt::FloorSize,
        Opt::Format,
        Opt::Growing,
        Opt::LineLength,
        Opt::LineWidth,
        Opt::LineZ,
        Opt::MarkerZ,
        Opt::Origin,
        Opt::Openings,
        Opt::Output,
        Opt::OutDir,
        Opt::Parent,
        Opt::Posts,
        Opt::PostSize,
        Opt::PxPerM,
        Opt::ResizeFloor,
        Opt::Rotation,
        Opt::Size,
        Opt::Start,
        Opt::WallHeight,
        Opt::WallLength,
        Opt::WallThickness,
        Opt::Width,
    ];

    /// The option's name in the neutral wording: `line-length`.
    fn neutral(self) -> &'static str {
        match self {
            Opt::Algo => "algo",
            Opt::Api => "api",
            Opt::Bias => "bias",
            Opt::Braid => "braid",
            Opt::CellSize => "cell-size",
            Opt::Draw => "draw",
            Opt::End => "end",
            Opt::Floor => "floor",
            Opt::FloorSize => "floor-size",
            Opt::Format => "format",
            Opt::Growing => "growing",
            Opt::LineLength => "line-length",
            Opt::LineWidth => "line-width",
            Opt::LineZ => "line-z",
            Opt::MarkerZ => "marker-z",
            Opt::Origin => "origin",
            Opt::Openings => "openings",
            Opt::Output => "output",
            Opt::OutDir => "out-dir",
            Opt::Parent => "parent",
            Opt::Posts => "posts",
            Opt::PostSize => "post-size",
            Opt::PxPerM => "px-per-m",
            Opt::ResizeFloor => "resize-floor",
            Opt::Rotation => "rotation",
            Opt::Size => "size",
            Opt::Start => "start",
            Opt::WallHeight => "wall-height",
            Opt::WallLength => "wall-length",
            Opt::WallThickness => "wall-thickness",
            Opt::Width => "width",
        }
    }
}

/// The value an option is given in a [`Setting`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Value {
    /// A number, as the message shows it (`0.3`, `1e308`).
    Number(String),
    /// A word or other text (`mesh`, `farthest-pair`, `start,end`): Python quotes it.
    Word(String),
    /// A stand-in for a value the user chooses (`NAME`, `FILE.svg`): written as is.
    Placeholder(&'static str),
    /// A flag turned on: the command line's bare `--posts`, Python's `posts=True`.
    On,
}

impl Value {
    /// A number as text.
    pub fn number(shown: impl fmt::Display) -> Self {
        Value::Number(shown.to_string())
    }

    /// A word as text.
    pub fn word(word: impl fmt::Display) -> Self {
        Value::Word(word.to_string())
    }
}

/// An option with its value: `--line-length 0.3`, `line_length=0.3`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Setting {
    /// The option.
    pub opt: Opt,
    /// Its value.
    pub value: Value,
}

/// One part of a [`Message`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Part {
    /// Text as it is, naming no option.
    Text(String),
    /// An option named alone (`--px-per-m`, `px_per_m`).
    Opt(Opt),
    /// Options given together, in order (`--line-length 0.3 --line-width 0.05`,
    /// `line_length=0.3, line_width=0.05`).
    Settings(Vec<Setting>),
    /// A call of `generate` with these settings, to make a maze anew (`vrep-maze generate
    /// --cell-size 0.5`, `vrep_maze.generate(cell_size=0.5)`).
    Generate(Vec<Setting>),
}

/// How an adapter words options: the command line's flags, Python's keyword arguments.
pub trait Wording {
    /// An option named alone.
    fn option(&self, opt: Opt) -> String;
    /// An option given `value`.
    fn setting(&self, opt: Opt, value: &Value) -> String;
    /// What stands between settings given together.
    fn separator(&self) -> &str;
    /// A call of `generate` with `settings` (already worded and joined).
    fn generate(&self, settings: &str) -> String;
    /// A text part: as it is, unless the adapter rewords text it did not write itself.
    fn text(&self, text: &str) -> String {
        text.to_string()
    }
}

/// The neutral wording of [`Message`]'s `Display` (`line-length`, `line-length=0.3`,
/// `posts`), for a library's own `Display` of an error that holds messages.
pub struct Neutral;

impl Wording for Neutral {
    fn option(&self, opt: Opt) -> String {
        opt.neutral().to_string()
    }

    fn setting(&self, opt: Opt, value: &Value) -> String {
        match value {
            Value::Number(v) | Value::Word(v) => format!("{}={v}", opt.neutral()),
            Value::Placeholder(v) => format!("{}={v}", opt.neutral()),
            Value::On => opt.neutral().to_string(),
        }
    }

    fn separator(&self) -> &str {
        ", "
    }

    fn generate(&self, settings: &str) -> String {
        format!("generate {settings}")
    }
}

/// A line that may name options, for an adapter to word ([`Message::worded`]).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Message(Vec<Part>);

impl Message {
    /// A message of `text` alone.
    pub fn text(text: impl Into<String>) -> Self {
        Message::default().and(text)
    }

    /// A message that starts by naming `opt`.
    pub fn opt(opt: Opt) -> Self {
        Message::default().and_opt(opt)
    }

    /// A message that starts with `opt` given `value`.
    pub fn setting(opt: Opt, value: Value) -> Self {
        Message::default().and_setting(opt, value)
    }

    /// This message followed by `text`.
    pub fn and(mut self, text: impl Into<String>) -> Self {
        let text = text.into();
        match self.0.last_mut() {
            Some(Part::Text(last)) => last.push_str(&text),
            _ if text.is_empty() => {}
            _ => self.0.push(Part::Text(text)),
        }
        self
    }

    /// This message followed by `opt` named alone.
    pub fn and_opt(mut self, opt: Opt) -> Self {
        self.0.push(Part::Opt(opt));
        self
    }

    /// This message followed by `opt` given `value`.
    pub fn and_setting(self, opt: Opt, value: Value) -> Self {
        self.and_settings(vec![Setting { opt, value }])
    }

    /// This message followed by `settings`, given together.
    pub fn and_settings(mut self, settings: Vec<Setting>) -> Self {
        self.0.push(Part::Settings(settings));
        self
    }

    /// This message followed by a call of `generate` with `settings`.
    pub fn and_generate(mut self, settings: Vec<Setting>) -> Self {
        self.0.push(Part::Generate(settings));
        self
    }

    /// This message followed by `other`.
    pub fn and_message(mut self, other: Message) -> Self {
        for part in other.0 {
            self = match part {
                Part::Text(text) => self.and(text),
                part => {
                    self.0.push(part);
                    self
                }
            };
        }
        self
    }

    /// `text` followed by this message.
    pub fn after(self, text: impl Into<String>) -> Self {
        Message::text(text).and_message(self)
    }

    /// The parts, in order.
    pub fn parts(&self) -> &[Part] {
        &self.0
    }

    /// The message in `wording`'s words.
    pub fn worded(&self, wording: &dyn Wording) -> String {
        let mut out = String::new();
        for part in &self.0 {
            match part {
                Part::Text(text) => out.push_str(&wording.text(text)),
                Part::Opt(opt) => out.push_str(&wording.option(*opt)),
                Part::Settings(settings) => out.push_str(&joined(wording, settings)),
                Part::Generate(settings) => {
                    out.push_str(&wording.generate(&joined(wording, settings)));
                }
            }
        }
        out
    }
}

/// `settings` worded and joined by `wording`.
fn joined(wording: &dyn Wording, settings: &[Setting]) -> String {
    let worded: Vec<String> = settings
        .iter()
        .map(|s| wording.setting(s.opt, &s.value))
        .collect();
    worded.join(wording.separator())
}

impl From<String> for Message {
    fn from(text: String) -> Self {
        Message::text(text)
    }
}

impl From<&str> for Message {
    fn from(text: &str) -> Self {
        Message::text(text)
    }
}

impl fmt::Display for Message {
    /// The neutral wording (`line-length=0.3`): adapters word a message themselves.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.worded(&Neutral))
    }
}

impl std::error::Error for Message {}

/// A command-line-like wording for the library's own tests (`--line-length 0.3`), so
/// they read as the messages users see.
#[cfg(test)]
pub(crate) mod testing {
    use super::{Message, Opt, Value, Wording};

    /// Options as `--` and their neutral names.
    pub(crate) struct Dashes;

    impl Wording for Dashes {
        fn option(&self, opt: Opt) -> String {
            format!("--{}", opt.neutral())
        }

        fn setting(&self, opt: Opt, value: &Value) -> String {
            match value {
                Value::Number(v) | Value::Word(v) => format!("--{} {v}", opt.neutral()),
                Value::Placeholder(v) => format!("--{} {v}", opt.neutral()),
                Value::On => format!("--{}", opt.neutral()),
            }
        }

        fn separator(&self) -> &str {
            " "
        }

        fn generate(&self, settings: &str) -> String {
            format!("vrep-maze generate {settings}")
        }
    }

    /// `message` as [`Dashes`] words it.
    pub(crate) fn dashed(message: &Message) -> String {
        message.worded(&Dashes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_join_and_word_in_the_neutral_words() {
        let m = Message::text("use a smaller ")
            .and_opt(Opt::Size)
            .and(" or ")
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
            .and(".");
        assert_eq!(
            m.to_string(),
            "use a smaller size or posts, post-size=0.01."
        );
        assert_eq!(
            Message::text("a").and("b").and_message(Message::text("c")),
            Message::text("abc")
        );
        assert_eq!(
            Message::text("x").after("seed 1: "),
            Message::text("seed 1: x")
        );
    }
}
