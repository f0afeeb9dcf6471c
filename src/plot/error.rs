//! What can go wrong drawing a figure (the crate's error union, `crate::Error::Draw`, holds it).

/// A figure that cannot be drawn: plotters' error, as its text (plotters' error types are
/// generic over the drawing backend, which the figures are too).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct DrawError(pub(crate) String);
