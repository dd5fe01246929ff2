//! "Did you mean": the nearest candidates to a misspelt word (a leaf module).

#[cfg(test)]
thread_local! {
    /// How many times `distance` ran on this thread (the tests count the work).
    static COMPARED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The characters of `s`, lowercased (distances are case-insensitive).
fn lower(s: &str) -> Vec<char> {
    s.chars().flat_map(char::to_lowercase).collect()
}

/// The edit distance (insertions, deletions, substitutions) between `a` and `b`
/// (lowercased), or some number above `bound` once it is known to be above it; `row`
/// is a buffer. Time: O(|a| · |b|).
fn distance(a: &[char], b: &[char], bound: usize, row: &mut Vec<usize>) -> usize {
    #[cfg(test)]
    COMPARED.with(|c| c.set(c.get() + 1));
    row.clear();
    row.extend(0..=b.len());
    for (i, ca) in a.iter().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        let mut least = row[0];
        for (j, cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (diag + usize::from(ca != cb)).min(up + 1).min(row[j] + 1);
            diag = up;
            least = least.min(row[j + 1]);
        }
        // Every later row is at least this row's least value.
        if least > bound {
            return least;
        }
    }
    row[b.len()]
}

/// How many candidates next to a word, on each side, in each of the two orders a
/// [`Suggester`] keeps, are compared with it: at most `4 * NEIGHBOURS` per word,
/// however many candidates there are.
const NEIGHBOURS: usize = 4;

/// Words longer than this (in bytes) are not compared (a 100 MB attribute name).
const LONGEST: usize = 256;

/// Candidates ranked once, for any number of "did you mean" questions.
///
/// A word is compared with the candidates next to it in alphabetical order (which
/// share its beginning: a typo near the end) and in the alphabetical order of the
/// reversed texts (which share its end: a typo near the beginning), `NEIGHBOURS` on
/// each side of each, not with every candidate: so a question costs
/// O(log c + NEIGHBOURS · |word| · |candidate|) for `c` candidates, and a model with
/// many misspelt references is checked in O(r log c) comparisons, not O(r · c).
/// With at most `2 * NEIGHBOURS` candidates, every one is compared.
pub(crate) struct Suggester<'a> {
    /// The candidates (each once, at most `LONGEST` bytes) in the order given, with
    /// their lowercased characters.
    candidates: Vec<(&'a str, Vec<char>)>,
    /// Positions in `candidates`, sorted by lowercased text.
    forward: Vec<(String, usize)>,
    /// Positions in `candidates`, sorted by lowercased reversed text.
    backward: Vec<(String, usize)>,
}

impl<'a> Suggester<'a> {
    /// Ranks `candidates`. Time: O(c log c) for `c` candidates.
    pub(crate) fn new(candidates: impl IntoIterator<Item = &'a str>) -> Suggester<'a> {
        let mut seen = std::collections::HashSet::new();
        let candidates: Vec<(&'a str, Vec<char>)> = candidates
            .into_iter()
            .filter(|c| c.len() <= LONGEST && seen.insert(*c))
            .map(|c| (c, lower(c)))
            .collect();
        let mut forward: Vec<(String, usize)> =
            candidates.iter().enumerate().map(|(i, (_, l))| (l.iter().collect(), i)).collect();
        forward.sort();
        let mut backward: Vec<(String, usize)> =
            forward.iter().map(|(k, i)| (k.chars().rev().collect(), *i)).collect();
        backward.sort();
        Suggester { candidates, forward, backward }
    }

    /// Up to `n` candidates close enough to `word` to be what was meant (about a third
    /// of the longer word's length away at most, and at least one edit), nearest
    /// first, ties in the candidates' order; only the candidates next to `word` in the
    /// two orders are compared (see the type's docs).
    pub(crate) fn nearest(&self, word: &str, n: usize) -> Vec<&'a str> {
        if word.len() > LONGEST {
            return Vec::new();
        }
        let chars = lower(word);
        let key: String = chars.iter().collect();
        let rkey: String = chars.iter().rev().collect();
        let mut near: Vec<usize> = Vec::with_capacity(4 * NEIGHBOURS);
        for (order, k) in [(&self.forward, &key), (&self.backward, &rkey)] {
            let at = order.partition_point(|(t, _)| t < k);
            let from = at.saturating_sub(NEIGHBOURS);
            let to = (at + NEIGHBOURS).min(order.len());
            near.extend(order[from..to].iter().map(|(_, i)| *i));
        }
        near.sort_unstable();
        near.dedup();
        let mut row = Vec::new();
        let mut found: Vec<(usize, usize)> = near
            .into_iter()
            .filter_map(|i| {
                let other = &self.candidates[i].1;
                // Close enough: about a third of the longer word's length at most (a
                // length that differs by more is further than that).
                let bound = chars.len().max(other.len()).div_ceil(3);
                if chars.len().abs_diff(other.len()) > bound {
                    return None;
                }
                let d = distance(&chars, other, bound, &mut row);
                (d > 0 && d <= bound).then_some((d, i))
            })
            .collect();
        found.sort_unstable();
        found.into_iter().take(n).map(|(_, i)| self.candidates[i].0).collect()
    }
}

/// Up to `n` candidates close enough to `word` to be what was meant, nearest first
/// (see [`Suggester::nearest`]). Time: O(c log c) for `c` candidates (ranking them),
/// and at most `4 * NEIGHBOURS` edit distances.
pub(crate) fn nearest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    n: usize,
) -> Vec<&'a str> {
    if word.len() > LONGEST {
        return Vec::new();
    }
    Suggester::new(candidates).nearest(word, n)
}

/// The one nearest candidate, if any is close enough.
pub(crate) fn closest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    nearest(word, candidates, 1).into_iter().next()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_typos() {
        assert_eq!(distance(&lower("hinj"), &lower("Hinge"), 5, &mut Vec::new()), 2);
        assert!(distance(&lower("abcdef"), &lower("uvwxyz"), 1, &mut Vec::new()) > 1);
        assert_eq!(closest("hinj", ["slide", "hinge", "ball"]), Some("hinge"));
        assert_eq!(closest("rgb", ["rgba", "size"]), Some("rgba"));
        assert_eq!(closest("zzzzzz", ["rgba", "size"]), None);
        assert_eq!(closest("rgba", ["rgba"]), None, "an exact match is no suggestion");
        assert_eq!(nearest("torsoo", ["torso", "torso2", "leg"], 3), vec!["torso", "torso2"]);
    }

    /// A typo at either end is found among 20,000 names, and each question compares
    /// the word with at most `4 * NEIGHBOURS` of them.
    #[test]
    fn a_question_compares_a_bounded_number_of_candidates() {
        let names: Vec<String> = (0..20_000).map(|i| format!("joint_{i:05}_link")).collect();
        let s = Suggester::new(names.iter().map(String::as_str));
        for (word, want) in [
            ("joint_12345_lnk", "joint_12345_link"),
            ("jiont_12345_link", "joint_12345_link"),
            ("JOINT_00007_LINK", "joint_00007_link"),
        ] {
            COMPARED.with(|c| c.set(0));
            let got = s.nearest(word, 3);
            let compared = COMPARED.with(std::cell::Cell::get);
            assert!(compared <= 4 * NEIGHBOURS, "{word}: {compared} comparisons");
            if word.starts_with("JOINT") {
                // Case only: no edit, no suggestion of itself, but its neighbours.
                assert!(!got.contains(&want), "{got:?}");
            } else {
                assert_eq!(got.first(), Some(&want), "{word}");
            }
        }
    }

    /// With few candidates every one is compared: the same answers as comparing
    /// them all (ties in the candidates' order).
    #[test]
    fn few_candidates_are_all_compared() {
        let names = ["torso", "torsi", "leg", "torso2", "tor"];
        assert_eq!(nearest("torsa", names, 5), vec!["torso", "torsi", "torso2", "tor"]);
        assert_eq!(nearest("x", names, 3), Vec::<&str>::new());
        assert_eq!(nearest("torso", ["torso", "torso"], 3), Vec::<&str>::new());
    }
}
