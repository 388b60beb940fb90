//! What a copies draw does with the copies a scene already has: how many it reuses, removes
//! and pastes, and how the missing ones are pasted round by round.

/// What to do with existing copies.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Plan {
    /// Existing copies kept (in segment order after the template).
    pub reuse: Vec<i32>,
    /// Existing copies removed.
    pub remove: Vec<i32>,
    /// Number of copies to paste.
    pub paste: usize,
}

/// Reuses as many existing copies as needed, removes the rest, pastes the missing ones.
pub fn plan(existing: &[i32], copies_needed: usize) -> Plan {
    let keep = existing.len().min(copies_needed);
    Plan {
        reuse: existing[..keep].to_vec(),
        remove: existing[keep..].to_vec(),
        paste: copies_needed - keep,
    }
}

/// One pasting round: up to `max_blocks` copy-paste commands, each copying (a prefix of) the
/// lines available so far, together pasting at most `missing` copies. With `max_blocks` = 1
/// this is plain doubling; with b blocks the set grows (b+1)-fold per round trip.
pub fn paste_round(available: &[i32], missing: usize, max_blocks: usize) -> Vec<Vec<i32>> {
    let mut groups = Vec::new();
    let mut left = missing;
    while left > 0 && groups.len() < max_blocks.max(1) && !available.is_empty() {
        let n = left.min(available.len());
        groups.push(available[..n].to_vec());
        left -= n;
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plan_reuses_pastes_removes() {
        assert_eq!(
            plan(&[7, 8, 9], 2),
            Plan {
                reuse: vec![7, 8],
                remove: vec![9],
                paste: 0
            }
        );
        assert_eq!(
            plan(&[7], 4),
            Plan {
                reuse: vec![7],
                remove: vec![],
                paste: 3
            }
        );
        assert_eq!(paste_round(&[1], 5, 1), vec![vec![1]]);
        assert_eq!(
            paste_round(&[1, 2, 3], 5, 4),
            vec![vec![1, 2, 3], vec![1, 2]]
        );
        assert_eq!(paste_round(&[1, 2], 0, 4), Vec::<Vec<i32>>::new());
        // rounds needed for 1797 copies from one template with 16 blocks per round
        let (mut have, mut rounds) = (1usize, 0);
        while have < 1798 {
            have += paste_round(&vec![0; have], 1798 - have, 16)
                .iter()
                .map(Vec::len)
                .sum::<usize>();
            rounds += 1;
        }
        assert_eq!((have, rounds), (1798, 3));
    }
}
