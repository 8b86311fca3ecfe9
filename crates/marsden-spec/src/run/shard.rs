//! `--shard i/n`: the part of a sweep one job runs, so that a cluster's array jobs can split it.
//!
//! Members are dealt round-robin: shard `i` of `n` runs the members `k` with `k % n == i`
//! (so every shard gets a spread of the swept values, and shards differ by at most one
//! member). Rows keep their global member index.
//!
//! ```
//! use marsden_spec::sweep::Shard;
//!
//! let shard: Shard = "1/3".parse()?;
//! assert_eq!(shard.members(8), [1, 4, 7]);
//! assert!("3/3".parse::<Shard>().is_err());
//! # Ok::<(), String>(())
//! ```

use std::str::FromStr;

/// Shard `index` of `count` (`0 ≤ index < count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which shard (0-based).
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl Shard {
    /// The whole sweep (shard 0 of 1).
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// The member indices of this shard among `total` members, in order.
    pub fn members(self, total: usize) -> Vec<usize> {
        self.iter(total).collect()
    }

    /// The members of this shard, in order, without collecting them.
    pub fn iter(self, total: usize) -> impl Iterator<Item = usize> {
        (self.index..total).step_by(self.count)
    }

    /// The file-name suffix of this shard (`""` for the whole sweep, `.shard-1-of-3`).
    pub fn suffix(self) -> String {
        if self == Shard::ALL {
            String::new()
        } else {
            format!(".shard-{}-of-{}", self.index, self.count)
        }
    }
}

/// The whole sweep.
impl Default for Shard {
    fn default() -> Self {
        Shard::ALL
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let usage = "write the shard as `i/n` with 0 ≤ i < n, e.g. `--shard 0/4`";
        let Some((i, n)) = text.split_once('/') else {
            return Err(format!("`{text}` is not of the form i/n; {usage}"));
        };
        let parse = |s: &str, what: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|_| format!("{what} `{s}` is not a whole number; {usage}"))
        };
        let (index, count) = (parse(i, "the shard index")?, parse(n, "the shard count")?);
        if count == 0 {
            return Err(format!(
                "the shard count must be at least 1, got `{text}`; {usage}"
            ));
        }
        if index >= count {
            return Err(format!(
                "shard index {index} is outside 0..{count} (the shards of {count} are 0 to {}); {usage}",
                count - 1
            ));
        }
        Ok(Shard { index, count })
    }
}
