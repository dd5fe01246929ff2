//! The order of a parent's children in the new version against the old: which keep
//! their relative order (the rest are [`Change::Moved`](super::Change::Moved)).

use crate::model::tree::Node;

/// One child in the new order, as matched against the old children.
pub(super) enum Unit<'m> {
    /// A chunk both versions share: old chunk start, new chunk start, its items.
    Shared(usize, usize, &'m [Node]),
    /// A child of both: old position, new position, old node, new node.
    Both(usize, usize, &'m Node, &'m Node),
    /// A child only the new version has under this parent: position, node.
    New(usize, &'m Node),
}

/// Which units (in the new order) keep their relative old order: a heaviest
/// increasing subsequence by old position, a shared chunk weighing its length.
/// Units that are not children of both versions are "kept". O(u log u).
pub(super) fn in_order(units: &[Unit<'_>]) -> Vec<bool> {
    // (unit index, old position, weight) of the units both versions have here.
    let both: Vec<(usize, usize, usize)> = units
        .iter()
        .enumerate()
        .filter_map(|(i, u)| match u {
            Unit::Shared(old, _, items) => Some((i, *old, items.len())),
            Unit::Both(old, _, _, _) => Some((i, *old, 1)),
            Unit::New(..) => None,
        })
        .collect();
    let mut kept = vec![true; units.len()];
    if both.windows(2).all(|w| w[0].1 < w[1].1) {
        return kept;
    }
    let n = both.len();
    let mut by_old: Vec<usize> = (0..n).collect();
    by_old.sort_by_key(|&k| both[k].1);
    let mut rank = vec![0; n];
    for (r, &k) in by_old.iter().enumerate() {
        rank[k] = r + 1;
    }
    // A Fenwick tree over ranks of (best weight ending there, its unit).
    let mut tree: Vec<(usize, usize)> = vec![(0, usize::MAX); n + 1];
    let mut best = vec![0; n];
    let mut prev = vec![usize::MAX; n];
    for k in 0..n {
        let mut r = rank[k] - 1;
        let mut q = (0, usize::MAX);
        while r > 0 {
            if tree[r].0 > q.0 {
                q = tree[r];
            }
            r &= r - 1;
        }
        best[k] = q.0 + both[k].2;
        prev[k] = q.1;
        let mut r = rank[k];
        while r <= n {
            if best[k] > tree[r].0 {
                tree[r] = (best[k], k);
            }
            r += r & r.wrapping_neg();
        }
    }
    for (i, _, _) in &both {
        kept[*i] = false;
    }
    let mut k = (0..n).max_by_key(|&k| best[k]).unwrap_or(usize::MAX);
    while k != usize::MAX {
        kept[both[k].0] = true;
        k = prev[k];
    }
    kept
}
