//! The options of parameterised algorithms: `--growing` (growing tree) and `--bias`
//! (binary tree), how they are written, parsed, and recorded in a layout.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::maze::Direction;
use crate::wording::{Message, Opt, Value};

/// Options recorded in a layout's `generator.options`; absent fields are omitted, so an
/// algorithm without options records `{}`. Keys serialise in this fixed order.
#[derive(
    Debug, Clone, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct AlgorithmOptions {
    /// Growing tree's cell selection (`newest`, `oldest`, `random`, `middle`, `mix:P`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growing: Option<String>,
    /// Binary tree's bias (`ne`, `nw`, `se`, `sw`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bias: Option<String>,
}

impl AlgorithmOptions {
    /// The options present, as `(name, value)` pairs in serialisation order.
    pub fn pairs(&self) -> Vec<(&'static str, String)> {
        let mut pairs = Vec::new();
        if let Some(growing) = &self.growing {
            pairs.push(("growing", growing.clone()));
        }
        if let Some(bias) = &self.bias {
            pairs.push(("bias", bias.clone()));
        }
        pairs
    }
}

/// A probability in `[0, 1]` in millionths, so it compares, hashes and prints exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MixRatio(u32);

impl MixRatio {
    /// Millionths in one.
    pub const SCALE: u32 = 1_000_000;

    /// The ratio `millionths / 1_000_000`, if at most one.
    pub const fn from_millionths(millionths: u32) -> Option<Self> {
        if millionths <= Self::SCALE {
            Some(Self(millionths))
        } else {
            None
        }
    }

    /// The ratio in millionths.
    pub const fn millionths(self) -> u32 {
        self.0
    }

    /// Parses a decimal in `[0, 1]` with at most six decimal places (`0.5`, `1`, `.25`).
    /// More places are refused rather than rounded, so the value prints back as written.
    pub fn parse(s: &str) -> Result<Self, String> {
        let bad = || format!("'{s}' is not a probability from 0 to 1 with at most 6 decimals");
        let (whole, fraction) = s.split_once('.').unwrap_or((s, ""));
        let digits = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
        if (whole.is_empty() && fraction.is_empty())
            || !digits(whole)
            || !digits(fraction)
            || fraction.len() > 6
            || whole.len() > 7
        {
            return Err(bad());
        }
        let whole: u32 = if whole.is_empty() {
            0
        } else {
            whole.parse().map_err(|_| bad())?
        };
        let mut millionths: u32 = 0;
        for (place, digit) in fraction.bytes().enumerate() {
            millionths += u32::from(digit - b'0') * 10u32.pow(5 - place as u32);
        }
        whole
            .checked_mul(Self::SCALE)
            .and_then(|w| w.checked_add(millionths))
            .and_then(Self::from_millionths)
            .ok_or_else(bad)
    }
}

impl fmt::Display for MixRatio {
    /// The shortest decimal: `0`, `1`, `0.5`, `0.000001`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let whole = self.0 / Self::SCALE;
        let fraction = self.0 % Self::SCALE;
        if fraction == 0 {
            return write!(f, "{whole}");
        }
        let digits = format!("{fraction:06}");
        write!(f, "{whole}.{}", digits.trim_end_matches('0'))
    }
}

/// Which active cell the growing tree extends next (`--growing`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum GrowingMode {
    /// The most recently added cell: behaves like DFS (long corridors, few dead ends).
    #[default]
    Newest,
    /// The oldest cell: long straight corridors fanning out from the start.
    Oldest,
    /// A uniformly random active cell: Prim-like, many short dead ends.
    Random,
    /// The middle cell of the active list (in insertion order).
    Middle,
    /// The newest cell with probability P, otherwise a random one (`mix:P`).
    Mix(MixRatio),
}

impl GrowingMode {
    /// The `--growing` words, `mix:P` standing for a mix with P a probability: for help,
    /// errors and completions.
    pub const WORDS: [&'static str; 5] = ["newest", "oldest", "random", "middle", "mix:P"];

    /// Parses a `--growing` value: `newest`, `oldest`, `random`, `middle` or `mix:P` with
    /// P a probability such as `0.75`.
    pub fn parse(s: &str) -> Result<Self, Message> {
        let lower = s.to_ascii_lowercase();
        match lower.as_str() {
            "newest" => Ok(Self::Newest),
            "oldest" => Ok(Self::Oldest),
            "random" => Ok(Self::Random),
            "middle" => Ok(Self::Middle),
            _ => match lower.strip_prefix("mix:") {
                Some(p) => MixRatio::parse(p).map(Self::Mix).map_err(|e| {
                    Message::setting(Opt::Growing, Value::word("mix:P")).and(format!(": {e}"))
                }),
                None => Err(format!(
                    "unknown growing mode '{s}' (known: {})",
                    Self::WORDS.join(", ")
                )
                .into()),
            },
        }
    }
}

impl fmt::Display for GrowingMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Newest => f.write_str("newest"),
            Self::Oldest => f.write_str("oldest"),
            Self::Random => f.write_str("random"),
            Self::Middle => f.write_str("middle"),
            Self::Mix(p) => write!(f, "mix:{p}"),
        }
    }
}

impl FromStr for GrowingMode {
    type Err = Message;

    fn from_str(s: &str) -> Result<Self, Message> {
        Self::parse(s)
    }
}

/// The two directions a binary tree carves towards (`--bias`); the two grid sides they
/// face become one straight corridor each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Bias {
    /// North and east (`ne`): the north row and the east column are corridors.
    #[default]
    NorthEast,
    /// North and west (`nw`).
    NorthWest,
    /// South and east (`se`).
    SouthEast,
    /// South and west (`sw`).
    SouthWest,
}

impl Bias {
    /// All four, in the order help texts list them.
    pub const ALL: [Bias; 4] = [
        Bias::NorthEast,
        Bias::NorthWest,
        Bias::SouthEast,
        Bias::SouthWest,
    ];

    /// The `--bias` value: `ne`, `nw`, `se` or `sw`.
    pub const fn name(self) -> &'static str {
        match self {
            Bias::NorthEast => "ne",
            Bias::NorthWest => "nw",
            Bias::SouthEast => "se",
            Bias::SouthWest => "sw",
        }
    }

    /// The vertical and the horizontal direction carved towards.
    pub const fn directions(self) -> (Direction, Direction) {
        match self {
            Bias::NorthEast => (Direction::North, Direction::East),
            Bias::NorthWest => (Direction::North, Direction::West),
            Bias::SouthEast => (Direction::South, Direction::East),
            Bias::SouthWest => (Direction::South, Direction::West),
        }
    }

    /// Parses a `--bias` value (case-insensitive).
    pub fn parse(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|b| b.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| {
                let known = Self::ALL.map(Bias::name).join(", ");
                format!("unknown bias '{s}' (known: {known})")
            })
    }
}

impl fmt::Display for Bias {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Bias {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mix_ratios_parse_and_print_exactly() {
        for (text, millionths, printed) in [
            ("0", 0, "0"),
            ("1", 1_000_000, "1"),
            ("1.0", 1_000_000, "1"),
            ("0.5", 500_000, "0.5"),
            (".25", 250_000, "0.25"),
            ("0.000001", 1, "0.000001"),
            ("0.750", 750_000, "0.75"),
        ] {
            let ratio = MixRatio::parse(text).unwrap();
            assert_eq!(ratio.millionths(), millionths, "{text}");
            assert_eq!(ratio.to_string(), printed, "{text}");
            assert_eq!(MixRatio::parse(printed), Ok(ratio));
        }
        for bad in [
            "",
            ".",
            "-0.5",
            "1.5",
            "2",
            "0.1234567",
            "0,5",
            "nan",
            "1e-3",
            "+1",
            " 1",
        ] {
            assert!(MixRatio::parse(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn growing_modes_round_trip() {
        for text in [
            "newest", "oldest", "random", "middle", "mix:0.5", "mix:1", "mix:0",
        ] {
            let mode: GrowingMode = text.parse().unwrap();
            assert_eq!(mode.to_string(), text);
        }
        assert_eq!(GrowingMode::parse("OLDEST"), Ok(GrowingMode::Oldest));
        assert!(
            GrowingMode::parse("mix:2")
                .unwrap_err()
                .to_string()
                .contains("mix:P")
        );
        assert!(GrowingMode::parse("mix").is_err());
        assert!(
            GrowingMode::parse("widest")
                .unwrap_err()
                .to_string()
                .contains("newest")
        );
    }

    #[test]
    fn biases_round_trip() {
        for bias in Bias::ALL {
            assert_eq!(bias.name().parse::<Bias>(), Ok(bias));
            assert_eq!(bias.to_string().to_uppercase().parse::<Bias>(), Ok(bias));
        }
        assert!(Bias::parse("north").unwrap_err().contains("ne, nw, se, sw"));
    }
}
