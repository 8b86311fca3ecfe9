//! "Did you mean …?": the closest known name by edit distance.

/// The largest edit distance at which a name is suggested.
const MAX_DISTANCE: usize = 2;

/// The candidate closest to `name`: edit distance at most 2, and at most a third of the
/// candidate's length (but at least 1), and less than its length, so short names are not
/// "corrected" into unrelated ones. Ties go to the first candidate in iteration order.
///
/// ```
/// use marsden_expr::closest;
/// assert_eq!(closest("thetadot", ["theta", "theta_dot"]), Some("theta_dot"));
/// assert_eq!(closest("omega", ["theta", "theta_dot"]), None);
/// ```
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (edit_distance(name, c), c))
        .filter(|&(d, c)| {
            let len = c.chars().count();
            d < len && d <= MAX_DISTANCE.min((len / 3).max(1))
        })
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// Optimal-string-alignment distance: insertions, deletions, substitutions and transpositions
/// of adjacent characters each cost 1.
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // rows[k][j]: distance between a[..i-2+k] and b[..j], for the last three rows i-2, i-1, i.
    let mut prev2 = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(prev2[j - 2] + 1);
            }
            cur[j] = d;
        }
        std::mem::swap(&mut prev2, &mut prev);
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("theta", "theta"), 0);
        assert_eq!(edit_distance("thetadot", "theta_dot"), 1);
        assert_eq!(edit_distance("thtea", "theta"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn closest_name() {
        let names = ["g", "l", "m", "theta", "theta_dot"];
        assert_eq!(closest("thetadot", names), Some("theta_dot"));
        assert_eq!(closest("thta", names), Some("theta"));
        assert_eq!(closest("omega", names), None);
        assert_eq!(closest("x", names), None);
        assert_eq!(closest("foo", ["cos", "sin"]), None);
        assert_eq!(closest("cso", ["cos", "sin"]), Some("cos"));
    }
}
