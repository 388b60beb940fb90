//! `vrep-maze batch --where`: only the mazes whose metrics meet the condition are kept (the
//! same command, the same manifest), and a bad condition is one line naming the position and
//! the problem, exit 2, before any maze is made.

use crate::support::bin;
use predicates::str::contains;
use std::fs;
use tempfile::TempDir;

fn manifest(dir: &std::path::Path, condition: &str) -> Vec<serde_json::Value> {
    bin()
        .args([
            "batch", "-q", "--size", "8x8", "--seeds", "0..12", "--where", condition,
        ])
        .arg("--out-dir")
        .arg(dir)
        .assert()
        .success();
    fs::read_to_string(dir.join("manifest.jsonl"))
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect()
}

#[test]
fn keeps_only_mazes_meeting_the_condition_the_same_every_run() {
    let (one, two) = (TempDir::new().unwrap(), TempDir::new().unwrap());
    let condition = "solution_cells >= 30 and dead_ends <= 9";
    let kept = manifest(one.path(), condition);
    assert!(!kept.is_empty() && kept.len() < 12, "{}", kept.len());
    for entry in &kept {
        let metrics = &entry["metrics"];
        assert!(metrics["solution_cells"].as_u64().unwrap() >= 30, "{entry}");
        assert!(metrics["dead_ends"].as_u64().unwrap() <= 9, "{entry}");
    }
    let again = manifest(two.path(), condition);
    assert_eq!(kept, again);
}

#[test]
fn a_bad_condition_names_the_metric_and_the_position() {
    let dir = TempDir::new().unwrap();
    for (condition, needle) in [
        (
            "solution_length >= 40",
            "at position 0: unknown metric 'solution_length'",
        ),
        (
            "loops >= 1 or cells > 2",
            "at position 11: expected 'and' or the end",
        ),
    ] {
        bin()
            .args(["batch", "--seeds", "0..3", "--where", condition])
            .arg("--out-dir")
            .arg(dir.path().join("out"))
            .assert()
            .code(2)
            .stderr(contains(needle));
    }
    assert!(!dir.path().join("out").exists());
}

/// `pNN` compares with the metric's percentile over the batch's seeds: `solution_cells >= p75`
/// keeps the longest quarter (ties included), and no dropped maze has a longer solution than
/// a kept one.
#[test]
fn a_percentile_keeps_the_hardest_share_of_the_batch() {
    let (all, hard) = (TempDir::new().unwrap(), TempDir::new().unwrap());
    let every = manifest(all.path(), "cells >= 0");
    assert_eq!(every.len(), 12);
    let kept = manifest(hard.path(), "solution_cells >= p75");
    let length = |e: &serde_json::Value| e["metrics"]["solution_cells"].as_u64().unwrap();
    let mut lengths: Vec<u64> = every.iter().map(length).collect();
    lengths.sort();
    // nearest rank: the 9th of 12
    let threshold = lengths[8];
    let want: Vec<u64> = every
        .iter()
        .filter(|e| length(e) >= threshold)
        .map(|e| e["seed"].as_u64().unwrap())
        .collect();
    let got: Vec<u64> = kept.iter().map(|e| e["seed"].as_u64().unwrap()).collect();
    assert_eq!(got, want);
    assert!((3..12).contains(&got.len()), "{got:?}");
}
