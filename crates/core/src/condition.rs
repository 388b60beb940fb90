//! A condition over a maze's metrics, as `batch --where` takes it:
//! `solution_cells >= 40 and dead_ends <= 12`. Comparisons (`<`, `<=`, `>`, `>=`, `==`,
//! `!=`) of a metric with a number, joined by `and`. The metrics are the layout's
//! ([`Metrics`]'s fields) and `dead_end_percent`. A number may be a percentile of the same
//! metric over the batch's mazes, `p0` to `p100` (`solution_cells >= p80`: the hardest fifth
//! by solution length), which [`Condition::resolved`] turns into a number.

use std::str::FromStr;

use crate::maze::Metrics;

/// The names a condition may compare, in the manifest's order.
pub const METRICS: [&str; 11] = [
    "cells",
    "passages",
    "loops",
    "solution_cells",
    "solution_turns",
    "decision_points",
    "dead_ends",
    "junctions",
    "straights",
    "diameter_cells",
    "dead_end_percent",
];

/// A comparison operator.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Operator {
    Less,
    LessOrEqual,
    Greater,
    GreaterOrEqual,
    Equal,
    NotEqual,
}

impl Operator {
    /// Longest first, so `<=` is not read as `<`.
    const ALL: [(&'static str, Operator); 6] = [
        ("<=", Operator::LessOrEqual),
        (">=", Operator::GreaterOrEqual),
        ("==", Operator::Equal),
        ("!=", Operator::NotEqual),
        ("<", Operator::Less),
        (">", Operator::Greater),
    ];

    fn holds(self, left: f64, right: f64) -> bool {
        match self {
            Operator::Less => left < right,
            Operator::LessOrEqual => left <= right,
            Operator::Greater => left > right,
            Operator::GreaterOrEqual => left >= right,
            Operator::Equal => left == right,
            Operator::NotEqual => left != right,
        }
    }
}

/// What a metric is compared with.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Value {
    /// A number.
    Number(f64),
    /// The metric's `p`th percentile over a batch (nearest rank), not yet resolved.
    Percentile(u8),
}

/// One `metric operator number`.
#[derive(Debug, Clone, PartialEq)]
struct Comparison {
    metric: &'static str,
    operator: Operator,
    value: Value,
}

/// Comparisons that must all hold.
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    comparisons: Vec<Comparison>,
    text: String,
}

impl Condition {
    /// `true` if every comparison holds for `metrics`. A percentile not yet
    /// [resolved](Condition::resolved) holds for nothing.
    pub fn accepts(&self, metrics: &Metrics) -> bool {
        self.comparisons.iter().all(|c| match c.value {
            Value::Number(v) => c.operator.holds(value_of(metrics, c.metric), v),
            Value::Percentile(_) => false,
        })
    }

    /// Whether it compares with a percentile ([`Condition::resolved`] needs the batch).
    pub fn has_percentiles(&self) -> bool {
        self.comparisons
            .iter()
            .any(|c| matches!(c.value, Value::Percentile(_)))
    }

    /// This condition with every percentile replaced by its value over `batch` (nearest
    /// rank: the smallest value at least `p`% of the mazes reach or stay under; the
    /// smallest value for `p0`). An empty batch leaves nothing to compare with: the
    /// percentile then holds for nothing.
    pub fn resolved(&self, batch: &[Metrics]) -> Condition {
        let comparisons = self
            .comparisons
            .iter()
            .map(|c| match c.value {
                Value::Percentile(p) => {
                    let mut values: Vec<f64> =
                        batch.iter().map(|m| value_of(m, c.metric)).collect();
                    values.sort_by(f64::total_cmp);
                    let rank = (f64::from(p) / 100.0 * values.len() as f64).ceil() as usize;
                    let value = values.get(rank.max(1) - 1).copied();
                    Comparison {
                        value: value.map_or(Value::Percentile(p), Value::Number),
                        ..c.clone()
                    }
                }
                Value::Number(_) => c.clone(),
            })
            .collect();
        Condition {
            comparisons,
            text: self.text.clone(),
        }
    }

    /// The text it was parsed from.
    pub fn text(&self) -> &str {
        &self.text
    }
}

/// The value of the metric `name` (one of [`METRICS`]).
fn value_of(metrics: &Metrics, name: &str) -> f64 {
    match name {
        "cells" => metrics.cells as f64,
        "passages" => metrics.passages as f64,
        "loops" => metrics.loops as f64,
        "solution_cells" => metrics.solution_cells as f64,
        "solution_turns" => metrics.solution_turns as f64,
        "decision_points" => metrics.decision_points as f64,
        "dead_ends" => metrics.dead_ends as f64,
        "junctions" => metrics.junctions as f64,
        "straights" => metrics.straights as f64,
        "diameter_cells" => metrics.diameter_cells as f64,
        _ => metrics.dead_end_percent(),
    }
}

impl FromStr for Condition {
    type Err = String;

    /// Parses `text`; the error names the position (a character offset from 0) and what is
    /// wrong there.
    fn from_str(text: &str) -> Result<Condition, String> {
        let mut comparisons = Vec::new();
        let mut rest = text;
        loop {
            comparisons.push(comparison(text, &mut rest)?);
            let trimmed = rest.trim_start();
            if trimmed.is_empty() {
                break;
            }
            let after_and = trimmed
                .strip_prefix("and")
                .filter(|after| after.starts_with(char::is_whitespace))
                .ok_or_else(|| at(text, trimmed, "expected 'and' or the end"))?;
            rest = after_and;
        }
        Ok(Condition {
            comparisons,
            text: text.to_string(),
        })
    }
}

/// Parses one comparison at the start of `rest`, moving `rest` past it.
fn comparison(text: &str, rest: &mut &str) -> Result<Comparison, String> {
    let start = rest.trim_start();
    let name_end = start
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(start.len());
    let name = &start[..name_end];
    if name.is_empty() {
        return Err(at(text, start, "expected a metric name"));
    }
    let metric = METRICS.into_iter().find(|m| *m == name).ok_or_else(|| {
        at(
            text,
            start,
            &format!("unknown metric '{name}' (one of {})", METRICS.join(", ")),
        )
    })?;
    let after_name = start[name_end..].trim_start();
    let (symbol, operator) = Operator::ALL
        .into_iter()
        .find(|(symbol, _)| after_name.starts_with(symbol))
        .ok_or_else(|| at(text, after_name, "expected <, <=, >, >=, == or !="))?;
    let number_text = after_name[symbol.len()..].trim_start();
    let number_end = number_text
        .find(char::is_whitespace)
        .unwrap_or(number_text.len());
    let word = &number_text[..number_end];
    let value = match word.strip_prefix('p') {
        Some(digits) => digits
            .parse::<u8>()
            .ok()
            .filter(|p| *p <= 100)
            .map(Value::Percentile)
            .ok_or_else(|| at(text, number_text, "expected a percentile p0 to p100"))?,
        None => word
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .map(Value::Number)
            .ok_or_else(|| at(text, number_text, "expected a number or a percentile (p80)"))?,
    };
    *rest = &number_text[number_end..];
    Ok(Comparison {
        metric,
        operator,
        value,
    })
}

/// `problem` at the position where `tail` (a suffix of `text`) starts.
fn at(text: &str, tail: &str, problem: &str) -> String {
    let position = text[..text.len() - tail.len()].chars().count();
    format!("'{text}' at position {position}: {problem}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(solution_cells: u64, dead_ends: u64) -> Metrics {
        Metrics {
            cells: 100,
            passages: 99,
            loops: 0,
            solution_cells,
            solution_turns: 0,
            decision_points: 0,
            dead_ends,
            junctions: 0,
            straights: 0,
            diameter_cells: 0,
        }
    }

    #[test]
    fn every_comparison_must_hold() {
        let c: Condition = "solution_cells>=40 and dead_ends <= 12".parse().unwrap();
        assert!(c.accepts(&metrics(40, 12)));
        assert!(!c.accepts(&metrics(39, 12)));
        assert!(!c.accepts(&metrics(40, 13)));
        let percent: Condition = "dead_end_percent < 10".parse().unwrap();
        assert!(percent.accepts(&metrics(1, 9)));
        assert!(!percent.accepts(&metrics(1, 10)));
        let exact: Condition = "loops == 0 and cells != 99".parse().unwrap();
        assert!(exact.accepts(&metrics(1, 1)));
    }

    #[test]
    fn errors_name_the_position_and_the_problem() {
        let error = |text: &str| text.parse::<Condition>().unwrap_err();
        assert_eq!(
            error("solution_length >= 40"),
            format!(
                "'solution_length >= 40' at position 0: unknown metric 'solution_length' (one of {})",
                METRICS.join(", ")
            )
        );
        assert_eq!(
            error("loops >= 1 or cells > 2"),
            "'loops >= 1 or cells > 2' at position 11: expected 'and' or the end"
        );
        assert_eq!(
            error("loops => 1"),
            "'loops => 1' at position 6: expected <, <=, >, >=, == or !="
        );
        assert_eq!(
            error("loops >= x"),
            "'loops >= x' at position 9: expected a number or a percentile (p80)"
        );
        assert_eq!(
            error("loops >= p101"),
            "'loops >= p101' at position 9: expected a percentile p0 to p100"
        );
        assert_eq!(error(""), "'' at position 0: expected a metric name");
        assert_eq!(
            error("loops >= 1 and"),
            "'loops >= 1 and' at position 11: expected 'and' or the end"
        );
    }

    #[test]
    fn percentiles_are_resolved_over_the_batch_by_nearest_rank() {
        let c: Condition = "solution_cells >= p80 and dead_ends <= 12".parse().unwrap();
        assert!(c.has_percentiles());
        // unresolved, a percentile holds for nothing
        assert!(!c.accepts(&metrics(100, 0)));
        let batch: Vec<Metrics> = (1..=10).map(|k| metrics(k * 10, k)).collect();
        let r = c.resolved(&batch);
        assert!(!r.has_percentiles());
        // the 80th percentile of 10, 20, ..., 100 is 80 (rank 8 of 10)
        assert!(r.accepts(&metrics(80, 3)) && !r.accepts(&metrics(79, 3)));
        assert!(!r.accepts(&metrics(90, 13)));
        let kept = batch.iter().filter(|m| r.accepts(m)).count();
        assert_eq!(kept, 3);
        let ends: Condition = "solution_cells <= p0".parse().unwrap();
        let shortest = ends.resolved(&batch);
        assert_eq!(batch.iter().filter(|m| shortest.accepts(m)).count(), 1);
        // nothing to compare with: nothing is kept
        assert!(!c.resolved(&[]).accepts(&metrics(100, 0)));
        assert_eq!(r.text(), c.text());
    }
}
