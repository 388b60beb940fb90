//! Times knossos 1.2 generating mazes (no rendering) and prints one tab-separated line
//! per measurement: `label side median_seconds`, labels as in vrep-maze's benchmark.
//!
//! Sizes 100, 1000 and 2000 square, median of 3 runs; a size is skipped when the
//! previous one predicts (quadratically, as knossos's Kruskal and Prim grow) more than
//! `KNOSSOS_BUDGET_S` seconds (default 30). Runs in a thread with a 4 GiB stack: knossos's
//! recursive backtracker recurses once per cell.

use std::time::Instant;

use knossos::maze::*;

fn algorithm(label: &str) -> Box<dyn Algorithm> {
    match label {
        "dfs" => Box::new(RecursiveBacktracking),
        "prim" => Box::new(Prim::new()),
        "kruskal" => Box::new(Kruskal),
        "aldous-broder" => Box::new(AldousBroder),
        "hunt-and-kill" => Box::new(HuntAndKill::new()),
        "growing-tree newest" => Box::new(GrowingTree::new(Method::Newest)),
        "growing-tree oldest" => Box::new(GrowingTree::new(Method::Oldest)),
        "growing-tree random" => Box::new(GrowingTree::new(Method::Random)),
        "growing-tree middle" => Box::new(GrowingTree::new(Method::Middle)),
        "growing-tree mix:0.5" => Box::new(GrowingTree::new(Method::Newest50Random50)),
        "eller" => Box::new(Eller),
        "sidewinder" => Box::new(Sidewinder),
        "binary-tree ne" => Box::new(BinaryTree::new(Bias::NorthEast)),
        "recursive-division" => Box::new(RecursiveDivision),
        other => panic!("no knossos algorithm for {other}"),
    }
}

const LABELS: [&str; 14] = [
    "dfs",
    "prim",
    "kruskal",
    "aldous-broder",
    "hunt-and-kill",
    "growing-tree newest",
    "eller",
    "sidewinder",
    "binary-tree ne",
    "recursive-division",
    "growing-tree oldest",
    "growing-tree random",
    "growing-tree middle",
    "growing-tree mix:0.5",
];

fn time_once(label: &str, side: usize, seed: u64) -> f64 {
    let start = Instant::now();
    let maze = OrthogonalMazeBuilder::new()
        .width(side)
        .height(side)
        .seed(Some(seed))
        .algorithm(algorithm(label))
        .build();
    let elapsed = start.elapsed().as_secs_f64();
    std::hint::black_box(&maze);
    elapsed
}

fn main() {
    let budget: f64 = std::env::var("KNOSSOS_BUDGET_S")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30.0);
    let filters: Vec<String> = std::env::args().skip(1).collect();
    let worker = std::thread::Builder::new()
        .stack_size(4 << 30)
        .spawn(move || {
            println!("# knossos 1.2.0, label\tside\tmedian seconds");
            for label in LABELS {
                if !filters.is_empty() && !filters.iter().any(|f| label.starts_with(f.as_str())) {
                    continue;
                }
                let mut previous: Option<(usize, f64)> = None;
                for side in [100usize, 1000, 2000] {
                    if let Some((prev_side, prev_s)) = previous {
                        let growth = (side * side) as f64 / (prev_side * prev_side) as f64;
                        let predicted = prev_s * growth * growth;
                        if predicted > budget {
                            eprintln!(
                                "knossos {label}: skipping {side}x{side} (predicted up to {predicted:.0} s)"
                            );
                            break;
                        }
                    }
                    let runs = if side >= 1000 { 3 } else { 5 };
                    let mut times: Vec<f64> =
                        (0..runs).map(|seed| time_once(label, side, seed as u64)).collect();
                    times.sort_by(f64::total_cmp);
                    let median = times[times.len() / 2];
                    println!("{label}\t{side}\t{median:.6}");
                    eprintln!("knossos {label} {side}x{side}: {median:.4} s");
                    previous = Some((side, median));
                }
            }
        })
        .expect("spawn the timing thread");
    worker.join().expect("timing thread");
}
