//! Sobol' sensitivity indices from the outputs of a Saltelli design, with bootstrap intervals.
//!
//! For `d` sampled inputs and `N` base points the design has two independent `N x d`
//! matrices A and B and, for every input `i`, the matrix AB_i: A with column `i` taken from
//! B. The model runs on every row; this module takes the outputs y_A, y_B, y_AB_i (`N` values
//! each) and knows nothing of how the points were drawn. For every input it estimates
//!
//! - the first-order index S_i = V_i / Var(y), the share of the output's variance that input
//!   `i` explains alone, with the estimator of Saltelli et al. (2010), "Variance based
//!   sensitivity analysis of model output. Design and estimator for the total sensitivity
//!   index", Comput. Phys. Commun. 181, 259-270 (table 2, b):
//!   V_i = mean(y_B (y_AB_i - y_A));
//! - the total index ST_i = VT_i / Var(y), its share with all its interactions, with the
//!   estimator of Jansen (1999), "Analysis of variance designs for model output", Comput.
//!   Phys. Commun. 117, 35-43 (Saltelli et al. 2010, table 2, f):
//!   VT_i = mean((y_A - y_AB_i)^2) / 2;
//!
//! where Var(y) is the variance of the 2N pooled values of y_A and y_B (divided by 2N).
//!
//! y_B is centred on the pooled mean in V_i. That subtracts mean(y) mean(y_AB_i - y_A), whose
//! expectation is 0, and makes the estimate independent of a shift of the output: uncentred,
//! an output such as a peak acceleration with a large mean and a small spread would add to
//! V_i a noise of standard deviation near |mean(y)| sd(y_AB_i - y_A) / sqrt(N) (SALib's
//! `sobol.analyze` standardises the output first, to the same effect).
//!
//! Each index has a 95 % percentile bootstrap interval: a replicate resamples the N base
//! points with replacement (the same rows of y_A, y_B and every y_AB_i) and recomputes every
//! index; the interval is the 2.5 and 97.5 percentiles of the replicates. Replicates are drawn
//! from a `Xoshiro256PlusPlus` seeded with the caller's seed, so intervals are reproducible.
//! Estimates are not clamped to [0, 1]: with few base points a small index may come out
//! slightly negative, and that is information about the noise.
//!
//! The folder: `estimate` (the indices and their intervals from the outputs alone),
//! `analysis` (the outputs of a Saltelli sweep file, estimated), `markdown` (its report).

mod analysis;
mod estimate;
mod markdown;

pub use analysis::{Analysis, OUTPUTS, analyse};
pub use estimate::{Index, Indices, Matrix, Outputs, SensitivityError, indices};
pub use markdown::{markdown, report};
