//! "Did you mean": the nearest candidates to a misspelt word (a leaf module).

/// The edit distance (insertions, deletions, substitutions) between `a` and `b`,
/// case-insensitive. Time: O(|a| · |b|).
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().flat_map(char::to_lowercase).collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().flat_map(char::to_lowercase).enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (diag + usize::from(ca != *cb)).min(up + 1).min(row[j] + 1);
            diag = up;
        }
    }
    row[b.len()]
}

/// Up to `n` candidates close enough to `word` to be what was meant (about a third of
/// the longer word's length away at most, and at least one edit), nearest first, ties in the
/// candidates' order. Time: O(candidates · |word| · |candidate|).
pub(crate) fn nearest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    n: usize,
) -> Vec<&'a str> {
    // Long words (a 100 MB attribute name) are not worth comparing.
    if word.len() > 256 {
        return Vec::new();
    }
    let len = word.chars().count();
    let mut found: Vec<(usize, &'a str)> = candidates
        .into_iter()
        .filter(|c| c.len() <= 256)
        .map(|c| (distance(word, c), c))
        .filter(|(d, c)| *d > 0 && *d <= len.max(c.chars().count()).div_ceil(3))
        .collect();
    found.sort_by_key(|(d, _)| *d);
    found.dedup_by(|a, b| a.1 == b.1);
    found.into_iter().take(n).map(|(_, c)| c).collect()
}

/// The one nearest candidate, if any is close enough.
pub(crate) fn closest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    nearest(word, candidates, 1).into_iter().next()
}

/// ` (did you mean 'a', 'b'?)`, or nothing.
pub(crate) fn hint(suggestions: &[impl AsRef<str>]) -> String {
    if suggestions.is_empty() {
        return String::new();
    }
    let list: Vec<String> =
        suggestions.iter().map(|s| format!("'{}'", crate::error::cut(s.as_ref()))).collect();
    format!(" (did you mean {}?)", list.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_typos() {
        assert_eq!(distance("hinj", "hinge"), 2);
        assert_eq!(closest("hinj", ["slide", "hinge", "ball"]), Some("hinge"));
        assert_eq!(closest("rgb", ["rgba", "size"]), Some("rgba"));
        assert_eq!(closest("zzzzzz", ["rgba", "size"]), None);
        assert_eq!(closest("rgba", ["rgba"]), None, "an exact match is no suggestion");
        assert_eq!(nearest("torsoo", ["torso", "torso2", "leg"], 3), vec!["torso", "torso2"]);
        assert_eq!(hint(&["a", "b"]), " (did you mean 'a', 'b'?)");
    }
}
