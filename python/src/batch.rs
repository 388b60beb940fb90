//! `batch`: many mazes, one per seed, as `vrep-maze batch` makes them, yielded as layouts.

use std::collections::VecDeque;
use std::sync::Arc;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyRange, PyString};
use rayon::prelude::*;
use std::sync::atomic::AtomicBool;
use vrep_maze::batch::{Filter, with_percentiles};
use vrep_maze::cli::Command;
use vrep_maze::layout::{self as library, build::Planned};
use vrep_maze::validate::checked;
use vrep_maze::wording::Message;

use crate::errors;
use crate::layout::Layout;
use crate::options;
use crate::wording::Keywords;
use crate::worker::{self, OnSignal};

/// Makes the layout of one seed.
type Maker = Arc<dyn Fn(u64) -> Result<library::Layout, String> + Send + Sync>;

/// Mazes made per core at a time: enough to keep every core busy, few enough that a
/// script which stops early has not waited for many more.
const PER_CORE: usize = 4;

/// An iterator over the layouts of a batch, in seed order, made in parallel a few at a
/// time as they are asked for. Each is byte-identical to `vrep-maze generate --seed N`
/// with the same options.
#[pyclass(module = "vrep_maze")]
pub struct Batch {
    /// Makes the layout of one seed, as `vrep-maze batch` does (any style).
    make: Maker,
    /// Every seed, in order.
    seeds: Vec<u64>,
    /// The index of the next seed to make.
    next: usize,
    /// Which mazes to keep (its percentiles resolved over every seed before the first maze
    /// is made: [`vrep_maze::batch::with_percentiles`]).
    filter: Filter,
    /// Made and kept, not yet yielded.
    ready: VecDeque<library::Layout>,
}

#[pymethods]
impl Batch {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&mut self, py: Python<'_>) -> PyResult<Option<Layout>> {
        if self.next == 0
            && self
                .filter
                .condition
                .as_ref()
                .is_some_and(|c| c.has_percentiles())
        {
            let (maker, filter, seeds) =
                (self.make.clone(), self.filter.clone(), self.seeds.clone());
            let resolve = move || {
                let metrics_of = |seed| {
                    maker(seed)
                        .map(|layout| layout.metrics)
                        .map_err(Message::from)
                };
                with_percentiles(filter, &seeds, &metrics_of, &AtomicBool::new(false))
            };
            let resolved = worker::run(py, resolve, OnSignal::Raise)?;
            self.filter = resolved.map_err(|e| PyValueError::new_err(e.worded(&Keywords)))?;
        }
        loop {
            if let Some(layout) = self.ready.pop_front() {
                return Layout::new(layout).map(Some);
            }
            if self.next == self.seeds.len() {
                return Ok(None);
            }
            let end = self
                .seeds
                .len()
                .min(self.next + PER_CORE * rayon::current_num_threads());
            let seeds = self.seeds[self.next..end].to_vec();
            self.next = end;
            let (maker, filter) = (self.make.clone(), self.filter.clone());
            let made = worker::run(py, move || make(&*maker, &seeds, &filter), OnSignal::Raise)?;
            self.ready = made.map_err(PyValueError::new_err)?.into();
        }
    }

    /// How many seeds the batch has (the filters may keep fewer mazes).
    fn __len__(&self) -> usize {
        self.seeds.len()
    }
}

/// The layouts of `seeds` that `filter` keeps, made in parallel, in seed order; each passes
/// the gate first, as in `vrep-maze batch`.
fn make(
    maker: &(dyn Fn(u64) -> Result<library::Layout, String> + Send + Sync),
    seeds: &[u64],
    filter: &Filter,
) -> Result<Vec<library::Layout>, String> {
    let made: Vec<Option<library::Layout>> = seeds
        .par_iter()
        .map(|&seed| {
            let layout = maker(seed).map_err(|e| format!("seed {seed}: {e}"))?;
            checked(&layout).map_err(|e| format!("seed {seed}: {e}"))?;
            Ok(filter.accepts(&layout.metrics).then_some(layout))
        })
        .collect::<Result<_, String>>()?;
    Ok(made.into_iter().flatten().collect())
}

/// Makes one maze per seed, as `vrep-maze batch` does, and yields their layouts in seed
/// order (a `Batch`, an iterator; `len()` is the number of seeds).
///
/// `seeds` is an int, an iterable of ints (`range(1000)`), or the command line's text
/// (`"0..1000"`, `"0..=99"`, `"1,5,9"`). The maze options are `generate`'s keywords
/// (`algo`, `size`, `braid`, ...); `min_solution=N` keeps only mazes whose solution has at
/// least N cells, `max_dead_ends=PCT` only those with at most PCT % dead ends,
/// `where="solution_cells >= 40 and dead_ends <= 12"` only those meeting the condition of
/// `vrep-maze batch --where` (a percentile, `where="solution_cells >= p80"`, is taken over
/// every seed's maze before the first is yielded; `where` is no Python keyword, and
/// `where_` is taken too). A refused
/// option raises `ValueError` with the command line's message. Mazes are made in parallel
/// on all cores, a few per core at a time, without the GIL; Ctrl-C raises
/// `KeyboardInterrupt` at once (nothing is written, so nothing is left half done).
#[pyfunction]
#[pyo3(signature = (seeds, algo=None, size=None, **options))]
pub fn batch(
    py: Python<'_>,
    seeds: &Bound<'_, PyAny>,
    algo: Option<Bound<'_, PyAny>>,
    size: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Batch> {
    let options = options::with(options, py, &[("algo", algo), ("size", size)])?;
    let seeds = format!("--seeds={}", seeds_text(seeds)?);
    // the layouts are yielded, not written: `.` only fills the command's place for a folder
    let argv = options::command_line("batch", &[&seeds, "--out-dir=."], &options)?;
    let Command::Batch(args) = options::parse(argv)? else {
        return Err(PyRuntimeError::new_err("batch parsed as another command"));
    };
    args.layout
        .check()
        .map_err(|e| errors::from_anyhow(py, &e))?;
    let options = args.layout;
    let make: Maker = Arc::new(move |seed| {
        options
            .plan(seed)
            .map(Planned::into_layout)
            .map_err(|e| errors::line(&e))
    });
    Ok(Batch {
        make,
        seeds: args.seeds.0,
        next: 0,
        filter: Filter {
            min_solution: args.min_solution,
            max_dead_end_percent: args.max_dead_ends,
            condition: args.condition,
        },
        ready: VecDeque::new(),
    })
}

/// `seeds` as the command line writes them: text as given, `range(a, b)` as `a..b`, other
/// iterables of ints comma-separated.
fn seeds_text(seeds: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(text) = seeds.cast::<PyString>() {
        return text.extract::<String>();
    }
    if seeds.is_instance_of::<PyInt>() {
        return seeds.str()?.extract::<String>();
    }
    if seeds.is_instance_of::<PyRange>() && seeds.getattr("step")?.extract::<i64>()? == 1 {
        let (start, stop) = (seeds.getattr("start")?, seeds.getattr("stop")?);
        return Ok(format!("{}..{}", start.str()?, stop.str()?));
    }
    let parts: Vec<String> = seeds
        .try_iter()?
        .map(|seed| seed?.str()?.extract::<String>())
        .collect::<PyResult<_>>()?;
    Ok(parts.join(","))
}
