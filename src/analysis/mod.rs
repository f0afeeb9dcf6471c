//! Analysis of a walk's motion: gait events, gait-cycle averaging, the check of the averaged
//! cycle against published norms, and biomechanical quality criteria (jerk, cyclicity, power).
pub mod criteria;
pub mod cycle;
pub mod events;
pub mod norms;

/// Smallest and largest finite value, if any.
pub(crate) fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}
