//! General numerics with no knowledge of walking: the ODE integrator with dense output and
//! events, bracketed root finding, fast sine / cosine / arctangent, and functions known by their
//! samples (interpolation, finite differences).
pub mod chebyshev;
pub mod minimise;
pub mod ode;
pub mod roots;
pub mod sampled;
pub mod smooth;
pub mod trig;
