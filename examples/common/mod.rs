//! What the study examples (`exploration`, `scaling`) share.

/// The integers of a command-line list: a range `a-b` (inclusive) or `a,b,c`.
pub fn list(s: &str) -> Vec<u64> {
    if let Some((a, b)) = s.split_once('-') {
        let (a, b): (u64, u64) = (a.parse().expect("a-b"), b.parse().expect("a-b"));
        return (a..=b).collect();
    }
    s.split(',')
        .map(|v| v.parse().expect("a list of integers"))
        .collect()
}
