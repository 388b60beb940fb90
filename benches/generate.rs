//! Generation benchmark: time (median of a few runs) and peak heap memory (bytes per
//! cell, from a counting global allocator) for every algorithm at 100x100, 1000x1000 and
//! 2000x2000, plus 4096x4096 (the size limit) for every algorithm but Aldous-Broder.
//!
//! Run: `cargo bench --bench generate` (or `bench/run.sh`, which also measures knossos
//! and prints the ratios). Arguments that are not flags pick algorithms by name, e.g.
//! `cargo bench --bench generate -- wilson eller`. Environment:
//! * `VREP_MAZE_BASELINE=FILE`: knossos timings (tab-separated `label side seconds`, label
//!   as in our first column, written by `bench/knossos`) to print side by side, with the
//!   ratio knossos time / our time at the largest size knossos was run at.
//! * `VREP_MAZE_BENCH_SKIP_4096=1`: leave out the 4096x4096 column.
//!
//! Timing assertions never go in tests; this binary only reports.

use std::alloc::{GlobalAlloc, Layout, System};
use std::collections::BTreeMap;
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use vrep_maze::generate::{Algorithm, GrowingMode, generate};
use vrep_maze::maze::Grid;

/// The system allocator, counting live bytes and their high-water mark.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let live = LIVE.fetch_add(bytes, Ordering::Relaxed) + bytes;
    PEAK.fetch_max(live, Ordering::Relaxed);
}

// SAFETY: every call is forwarded to `System` unchanged; only counters are added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let ptr = unsafe { System.alloc(layout) };
        if !ptr.is_null() {
            grew(layout.size());
        }
        ptr
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let ptr = unsafe { System.alloc_zeroed(layout) };
        if !ptr.is_null() {
            grew(layout.size());
        }
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let new = unsafe { System.realloc(ptr, layout, new_size) };
        if !new.is_null() {
            // A growing realloc may hold old and new blocks at once: count the peak so.
            grew(new_size);
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        new
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// One measurement: median seconds over `runs` and the peak heap growth in bytes.
#[derive(Clone, Copy)]
struct Sample {
    seconds: f64,
    fastest: f64,
    peak_bytes: usize,
    cells: usize,
}

impl Sample {
    fn bytes_per_cell(self) -> f64 {
        self.peak_bytes as f64 / self.cells as f64
    }
}

fn measure(algorithm: Algorithm, side: u64, runs: usize) -> Sample {
    let grid = Grid::new(side, side).expect("benchmark sizes are valid");
    let mut times = Vec::with_capacity(runs);
    let mut peak_bytes = 0;
    for run in 0..runs {
        let before = LIVE.load(Ordering::Relaxed);
        PEAK.store(before, Ordering::Relaxed);
        let start = Instant::now();
        let maze = generate(grid, algorithm, black_box(run as u64));
        let elapsed = start.elapsed().as_secs_f64();
        peak_bytes = peak_bytes.max(PEAK.load(Ordering::Relaxed) - before);
        black_box(&maze);
        drop(maze);
        times.push(elapsed);
    }
    times.sort_by(f64::total_cmp);
    Sample {
        seconds: times[times.len() / 2],
        fastest: times[0],
        peak_bytes,
        cells: grid.cell_count(),
    }
}

/// A label with options, e.g. `growing-tree (random)`.
fn label(algorithm: Algorithm) -> String {
    let options: Vec<String> = algorithm
        .option_pairs()
        .into_iter()
        .map(|(_, value)| value)
        .collect();
    if options.is_empty() {
        algorithm.name().to_string()
    } else {
        format!("{} {}", algorithm.name(), options.join(" "))
    }
}

/// knossos timings by (label, side): the largest side measured for each algorithm.
fn read_baseline() -> BTreeMap<String, Vec<(u64, f64)>> {
    let mut baseline: BTreeMap<String, Vec<(u64, f64)>> = BTreeMap::new();
    let Ok(path) = std::env::var("VREP_MAZE_BASELINE") else {
        return baseline;
    };
    let text =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("VREP_MAZE_BASELINE={path}: {e}"));
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let fields: Vec<&str> = line.split('\t').collect();
        if let [name, side, seconds] = fields[..]
            && let (Ok(side), Ok(seconds)) = (side.parse(), seconds.parse())
        {
            baseline
                .entry(name.to_string())
                .or_default()
                .push((side, seconds));
        }
    }
    baseline
}

fn ms(seconds: f64) -> String {
    if seconds < 0.01 {
        format!("{:.3}", seconds * 1e3)
    } else {
        format!("{:.1}", seconds * 1e3)
    }
}

fn main() {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let with_4096 = std::env::var_os("VREP_MAZE_BENCH_SKIP_4096").is_none();
    let baseline = read_baseline();
    let load = |when: &str| {
        let text = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
        let first: Vec<&str> = text.split_whitespace().take(3).collect();
        println!(
            "load average {when}: {} (cores: {})",
            first.join(" "),
            std::thread::available_parallelism().map_or(0, |n| n.get())
        );
    };
    load("before");

    let mut algorithms = Algorithm::ALL.to_vec();
    for mode in ["oldest", "random", "middle", "mix:0.5"] {
        algorithms.push(Algorithm::GrowingTree(GrowingMode::parse(mode).unwrap()));
    }
    algorithms.retain(|a| filters.is_empty() || filters.iter().any(|f| f == a.name()));

    println!(
        "| algorithm | 100² ms | 1000² ms | 2000² ms | 2000² fastest ms | 2000²/1000² | B/cell 2000² | 4096² ms | B/cell 4096² | knossos (largest size run) | knossos / ours |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|");
    for algorithm in algorithms {
        let slow = algorithm == Algorithm::AldousBroder;
        let small = measure(algorithm, 100, 11);
        let mid = measure(algorithm, 1000, if slow { 3 } else { 5 });
        let large = measure(algorithm, 2000, if slow { 1 } else { 5 });
        let huge = (with_4096 && !slow).then(|| measure(algorithm, 4096, 1));
        let name = label(algorithm);
        let (knossos, ratio) = match baseline.get(&name).and_then(|runs| runs.last()) {
            Some(&(side, seconds)) => {
                let ours = match side {
                    100 => small.seconds,
                    1000 => mid.seconds,
                    2000 => large.seconds,
                    other => measure(algorithm, other, 3).seconds,
                };
                (
                    format!("{} ms at {side}²", ms(seconds)),
                    format!("{:.1}x", seconds / ours),
                )
            }
            None => ("-".to_string(), "-".to_string()),
        };
        println!(
            "| {name} | {} | {} | {} | {} | {:.2}x | {:.2} | {} | {} | {knossos} | {ratio} |",
            ms(small.seconds),
            ms(mid.seconds),
            ms(large.seconds),
            ms(large.fastest),
            large.seconds / mid.seconds,
            large.bytes_per_cell(),
            huge.map_or("-".to_string(), |s| ms(s.seconds)),
            huge.map_or("-".to_string(), |s| format!("{:.2}", s.bytes_per_cell())),
        );
    }
    println!();
    load("after");
    println!(
        "Median of 11 runs at 100², 5 at 1000² and 2000² (Aldous-Broder: 3 and 1), 1 at 4096²; \
         seeds 0, 1, ...; B/cell = peak heap growth during generation / cells, maze included."
    );
}
