//! Datasets: many layouts at once, one per seed, with a manifest, in parallel.
//!
//! Each maze is written to `<algo>-<W>x<H>[-braid<P>]-seed<N>.json`; `manifest.jsonl`
//! holds one JSON line per maze (seed, file, metrics) in seed order. A file that already
//! holds exactly the maze is left alone, so re-running a batch only writes what changed;
//! every file is written atomically, so an interrupted batch leaves no half-written file.

use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use crate::atomic_file::{remove_stale_temporaries, write_atomically};
use crate::condition::Condition;
use crate::layout::json::to_string;
use crate::layout::{GenerateSpec, Layout, build_layout};
use crate::maze::Metrics;
use crate::wording::{Message, Opt};

/// The most seeds one batch takes.
pub const MAX_SEEDS: usize = 1_000_000;

/// Which mazes a batch keeps.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Filter {
    /// Keep only mazes whose solution has at least this many cells.
    pub min_solution: Option<u64>,
    /// Keep only mazes whose dead ends are at most this percentage of the cells.
    pub max_dead_end_percent: Option<f64>,
    /// Keep only mazes whose metrics meet this condition (`--where`).
    pub condition: Option<Condition>,
}

impl Filter {
    /// `true` if a maze with `metrics` is kept.
    pub fn accepts(&self, metrics: &Metrics) -> bool {
        self.min_solution
            .is_none_or(|min| metrics.solution_cells >= min)
            && self
                .max_dead_end_percent
                .is_none_or(|max| metrics.dead_end_percent() <= max)
            && self.condition.as_ref().is_none_or(|c| c.accepts(metrics))
    }
}

/// One line of `manifest.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ManifestEntry {
    /// The maze's seed.
    pub seed: u64,
    /// Its file, relative to the output directory.
    pub file: String,
    /// What it is like.
    pub metrics: Metrics,
    /// Seeds drawn for it: 1 plus the seeds just before it (in seed order, since the previous
    /// kept maze) whose maze the filter refused. 1 when nothing is filtered.
    pub seeds_drawn: u64,
}

/// What a batch did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// Layouts written (new or changed).
    pub written: usize,
    /// Layouts already on disk, byte for byte.
    pub unchanged: usize,
    /// Seeds whose maze the filter refused.
    pub filtered: usize,
    /// Seeds not made because the batch was stopped (see [`run`]'s `stop`).
    pub skipped: usize,
    /// Temporary files of an earlier, killed run that were removed first.
    pub stale_removed: usize,
    /// The manifest's path.
    pub manifest: PathBuf,
}

/// What happened to one seed.
enum Made {
    Written(ManifestEntry),
    Unchanged(ManifestEntry),
    Filtered,
    Skipped,
}

/// The file name of the maze `spec` describes.
pub fn file_name(spec: &GenerateSpec) -> String {
    let braid = if spec.braid > 0.0 {
        format!("-braid{}", spec.braid)
    } else {
        String::new()
    };
    format!(
        "{}-{}x{}{braid}-seed{}.json",
        spec.algorithm.name(),
        spec.grid.width(),
        spec.grid.height(),
        spec.seed
    )
}

/// Makes one layout per seed from `template` (its seed is replaced) into `out_dir`, in
/// parallel on all cores; `tick` is called once per seed done (for a progress bar). Once
/// `stop` is set, mazes in flight are finished and no new one is started; the manifest then
/// lists every maze made, in seed order, and [`Outcome::skipped`] counts the rest.
pub fn run(
    template: &GenerateSpec,
    seeds: &[u64],
    filter: Filter,
    out_dir: &Path,
    tick: &(dyn Fn() + Sync),
    stop: &AtomicBool,
) -> Result<Outcome, Message> {
    let make = |seed| {
        let spec = GenerateSpec {
            seed,
            ..template.clone()
        };
        let layout = build_layout(&spec).map_err(|e| e.after(format!("seed {seed}: ")))?;
        Ok((layout, file_name(&spec)))
    };
    run_with(&make, seeds, filter, out_dir, tick, stop)
}

/// Makes a layout and names its file for a seed: what a batch of any style needs.
pub type Maker<'a> = dyn Fn(u64) -> Result<(Layout, String), Message> + Sync + 'a;

/// [`run`] for layouts of any kind: `make` gives the layout of a seed and its file name
/// (relative to `out_dir`); every layout passes the gate before it is written.
pub fn run_with(
    make: &Maker<'_>,
    seeds: &[u64],
    filter: Filter,
    out_dir: &Path,
    tick: &(dyn Fn() + Sync),
    stop: &AtomicBool,
) -> Result<Outcome, Message> {
    if out_dir.exists() && !out_dir.is_dir() {
        return Err(Message::text(format!(
            "{}: exists and is not a directory (",
            out_dir.display()
        ))
        .and_opt(Opt::OutDir)
        .and(" names the directory that gets the layouts and manifest.jsonl)"));
    }
    fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let stale_removed =
        remove_stale_temporaries(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let metrics_of = |seed| make(seed).map(|(layout, _)| layout.metrics);
    let filter = with_percentiles(filter, seeds, &metrics_of, stop)?;
    let made: Vec<Made> = seeds
        .par_iter()
        .map(|&seed| {
            if stop.load(Ordering::SeqCst) {
                return Ok(Made::Skipped);
            }
            let result = make_one(make, seed, &filter, out_dir);
            tick();
            result
        })
        .collect::<Result<_, Message>>()?;
    let mut outcome = Outcome {
        manifest: out_dir.join("manifest.jsonl"),
        stale_removed,
        ..Outcome::default()
    };
    let mut entries = Vec::new();
    let mut drawn = 0;
    for result in made {
        drawn += 1;
        let kept = match result {
            Made::Written(entry) => {
                outcome.written += 1;
                entry
            }
            Made::Unchanged(entry) => {
                outcome.unchanged += 1;
                entry
            }
            Made::Filtered => {
                outcome.filtered += 1;
                continue;
            }
            Made::Skipped => {
                outcome.skipped += 1;
                continue;
            }
        };
        entries.push(ManifestEntry {
            seeds_drawn: drawn,
            ..kept
        });
        drawn = 0;
    }
    write_atomically(&outcome.manifest, |w| write_manifest(&entries, w))
        .map_err(|e| format!("{}: {e}", outcome.manifest.display()))?;
    Ok(outcome)
}

/// `filter` with its condition's percentiles ([`Condition::resolved`]) taken over the
/// mazes of every seed (`metrics_of` makes each once more, in parallel, until `stop` is
/// set); `filter` itself when it has none. The command line's and Python's `batch` both.
pub fn with_percentiles(
    filter: Filter,
    seeds: &[u64],
    metrics_of: &(dyn Fn(u64) -> Result<Metrics, Message> + Sync),
    stop: &AtomicBool,
) -> Result<Filter, Message> {
    let Some(condition) = filter.condition.as_ref().filter(|c| c.has_percentiles()) else {
        return Ok(filter);
    };
    let batch: Vec<Metrics> = seeds
        .par_iter()
        .filter(|_| !stop.load(Ordering::SeqCst))
        .map(|&seed| metrics_of(seed).map_err(|e| e.after(format!("seed {seed}: "))))
        .collect::<Result<_, Message>>()?;
    Ok(Filter {
        condition: Some(condition.resolved(&batch)),
        ..filter
    })
}

fn make_one(make: &Maker<'_>, seed: u64, filter: &Filter, out_dir: &Path) -> Result<Made, Message> {
    let (layout, file) = make(seed)?;
    // the gate every layout passes before anything is done with it
    crate::validate::checked(&layout).map_err(|e| {
        let said = Message::text(format!("seed {seed}: {e}: "));
        match e.problems.first() {
            Some(p) => said
                .and(format!("{}: ", p.location))
                .and_message(p.message.clone()),
            None => said,
        }
    })?;
    if !filter.accepts(&layout.metrics) {
        return Ok(Made::Filtered);
    }
    let path = out_dir.join(&file);
    let text = to_string(&layout);
    let entry = ManifestEntry {
        seed,
        file,
        metrics: layout.metrics,
        seeds_drawn: 1,
    };
    if fs::read(&path).is_ok_and(|old| old == text.as_bytes()) {
        return Ok(Made::Unchanged(entry));
    }
    write_atomically(&path, |w| w.write_all(text.as_bytes()))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Made::Written(entry))
}

fn write_manifest(entries: &[ManifestEntry], writer: &mut dyn Write) -> io::Result<()> {
    for entry in entries {
        serde_json::to_writer(&mut *writer, entry)?;
        writer.write_all(b"\n")?;
    }
    Ok(())
}

/// Why a seed list was refused ([`parse_seeds`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SeedsError {
    /// A part is no seed and no range.
    #[error("'{0}' is not a seed, a range A..B or A..=B")]
    NotASeed(String),
    /// A range holds no seed.
    #[error("'{0}' is an empty range")]
    Empty(String),
    /// The list holds more than [`MAX_SEEDS`].
    #[error("more than {MAX_SEEDS} seeds in '{0}'")]
    TooMany(String),
    /// A seed is listed twice.
    #[error("seed {seed} comes twice in '{list}': each seed makes one file, list it once")]
    Twice {
        /// The seed.
        seed: u64,
        /// The list as given.
        list: String,
    },
}

/// Parses a seed list: `N`, `A..B` (B excluded), `A..=B` (B included), or several of
/// these separated by commas.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, SeedsError> {
    let mut seeds = Vec::new();
    for part in text.split(',') {
        let part = part.trim();
        let number = |s: &str| {
            s.trim()
                .parse::<u64>()
                .map_err(|_| SeedsError::NotASeed(part.to_string()))
        };
        let (from, to) = if let Some((a, b)) = part.split_once("..=") {
            (number(a)?, number(b)?)
        } else if let Some((a, b)) = part.split_once("..") {
            let (a, b) = (number(a)?, number(b)?);
            if b <= a {
                return Err(SeedsError::Empty(part.to_string()));
            }
            (a, b - 1)
        } else {
            let n = number(part)?;
            (n, n)
        };
        if to < from {
            return Err(SeedsError::Empty(part.to_string()));
        }
        if (to - from) as u128 + seeds.len() as u128 >= MAX_SEEDS as u128 {
            return Err(SeedsError::TooMany(text.to_string()));
        }
        seeds.extend(from..=to);
    }
    let mut sorted = seeds.clone();
    sorted.sort_unstable();
    if let Some(twice) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(SeedsError::Twice {
            seed: twice[0],
            list: text.to_string(),
        });
    }
    Ok(seeds)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::maze::Grid;

    #[test]
    fn seed_lists_parse() {
        assert_eq!(parse_seeds("0..3"), Ok(vec![0, 1, 2]));
        assert_eq!(parse_seeds("0..=3"), Ok(vec![0, 1, 2, 3]));
        assert_eq!(parse_seeds("7, 9..11"), Ok(vec![7, 9, 10]));
        for twice in ["1,1", "0..10,5", "3..=4,4..6"] {
            let e = parse_seeds(twice).unwrap_err();
            assert!(e.to_string().contains("comes twice"), "{twice}: {e}");
        }
        for bad in ["", "a", "3..3", "5..=2", "0..=18446744073709551615", "1..x"] {
            assert!(parse_seeds(bad).is_err(), "{bad}");
        }
    }

    /// A stop flag that is never set.
    fn go() -> AtomicBool {
        AtomicBool::new(false)
    }

    #[test]
    fn a_stopped_batch_makes_nothing_new_and_lists_what_it_made() {
        let dir = tempfile::TempDir::new().unwrap();
        let template = GenerateSpec::course(Grid::new(6, 6).unwrap(), Algorithm::Dfs, 0);
        let seeds: Vec<u64> = (0..40).collect();
        let stop = AtomicBool::new(false);
        let made = std::sync::atomic::AtomicUsize::new(0);
        // stop after the fifth maze: those in flight finish, no new one starts
        let tick = || {
            if made.fetch_add(1, Ordering::SeqCst) + 1 == 5 {
                stop.store(true, Ordering::SeqCst);
            }
        };
        let outcome = run(
            &template,
            &seeds,
            Filter::default(),
            dir.path(),
            &tick,
            &stop,
        )
        .unwrap();
        assert!(outcome.skipped > 0, "{outcome:?}");
        assert_eq!(outcome.written + outcome.skipped, 40, "{outcome:?}");
        let manifest = fs::read_to_string(&outcome.manifest).unwrap();
        assert_eq!(manifest.lines().count(), outcome.written);
        let files = fs::read_dir(dir.path()).unwrap().count();
        assert_eq!(
            files,
            outcome.written + 1,
            "layouts + manifest, no temporaries"
        );
        let rerun = run(
            &template,
            &seeds,
            Filter::default(),
            dir.path(),
            &|| {},
            &go(),
        )
        .unwrap();
        assert_eq!(
            (rerun.written, rerun.unchanged),
            (40 - outcome.written, outcome.written)
        );
    }

    #[test]
    fn batches_write_once_and_filter() {
        let dir = tempfile::TempDir::new().unwrap();
        let template = GenerateSpec::course(Grid::new(8, 8).unwrap(), Algorithm::Prim, 0);
        let seeds: Vec<u64> = (0..12).collect();
        let first = run(
            &template,
            &seeds,
            Filter::default(),
            dir.path(),
            &|| {},
            &go(),
        )
        .unwrap();
        assert_eq!((first.written, first.unchanged, first.filtered), (12, 0, 0));
        let manifest = fs::read_to_string(&first.manifest).unwrap();
        assert_eq!(manifest.lines().count(), 12);
        assert!(manifest.starts_with("{\"seed\":0,\"file\":\"prim-8x8-seed0.json\",\"metrics\":{"));
        let again = run(
            &template,
            &seeds,
            Filter::default(),
            dir.path(),
            &|| {},
            &go(),
        )
        .unwrap();
        assert_eq!((again.written, again.unchanged), (0, 12));
        assert_eq!(fs::read_to_string(&again.manifest).unwrap(), manifest);

        let lengths_by_seed: Vec<u64> = manifest
            .lines()
            .map(|line| {
                let value: serde_json::Value = serde_json::from_str(line).unwrap();
                value["metrics"]["solution_cells"].as_u64().unwrap()
            })
            .collect();
        let mut lengths = lengths_by_seed.clone();
        lengths.sort_unstable();
        let median = lengths[6];
        let picky = Filter {
            min_solution: Some(median),
            ..Filter::default()
        };
        let out = tempfile::TempDir::new().unwrap();
        let filtered = run(&template, &seeds, picky, out.path(), &|| {}, &go()).unwrap();
        let kept = lengths.iter().filter(|&&l| l >= median).count();
        assert_eq!((filtered.written, filtered.filtered), (kept, 12 - kept));
        assert!(filtered.filtered > 0);
        for line in fs::read_to_string(&filtered.manifest).unwrap().lines() {
            let value: serde_json::Value = serde_json::from_str(line).unwrap();
            assert!(value["metrics"]["solution_cells"].as_u64().unwrap() >= median);
        }

        let condition = Filter {
            condition: Some(format!("solution_cells >= {median}").parse().unwrap()),
            ..Filter::default()
        };
        let out = tempfile::TempDir::new().unwrap();
        let same = run(&template, &seeds, condition, out.path(), &|| {}, &go()).unwrap();
        assert_eq!((same.written, same.filtered), (kept, 12 - kept));
        let drawn: u64 = fs::read_to_string(&same.manifest)
            .unwrap()
            .lines()
            .map(|line| serde_json::from_str::<serde_json::Value>(line).unwrap())
            .map(|entry| entry["seeds_drawn"].as_u64().unwrap())
            .sum();
        let last_kept = lengths_by_seed.iter().rposition(|&l| l >= median).unwrap() as u64;
        assert_eq!(drawn, last_kept + 1);
        assert_eq!(
            fs::read_to_string(&same.manifest).unwrap(),
            fs::read_to_string(&filtered.manifest).unwrap()
        );
    }
}
