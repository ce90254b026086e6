//! `[sampling]`: the RRT-like baseline planner of the paper's Section V (`shoal plan --method
//! rrt-like`, `src/sampling/`). The MPC planner ignores it.

use serde::{Deserialize, Serialize};

/// The tree of the RRT-like baseline (`src/sampling/`, docs/baseline.md).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sampling {
    /// 𝔯 (Section V): valid random samples drawn from every node of the tree at each step
    /// k = 1..K, its children.
    pub samples: usize,
    /// Nodes the tree keeps per step: when a step has more children, the best by score so far
    /// are kept (ours: the paper's full tree has Σ_k 𝔯^k nodes, 10¹⁴ at 𝔯 = 5, K = 20).
    pub tree_budget: usize,
    /// Draws per AUV before one sample is given up (the sample fails; the node draws its next).
    pub attempts: usize,
}

impl Default for Sampling {
    fn default() -> Self {
        Sampling {
            samples: 16,
            tree_budget: 200,
            attempts: 500,
        }
    }
}
