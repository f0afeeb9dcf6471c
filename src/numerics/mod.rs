//! General numerics with no knowledge of walking: the ODE integrator with dense output and
//! events, bracketed root finding, and fast sine / cosine / arctangent.
pub mod chebyshev;
pub mod minimise;
pub mod ode;
pub mod roots;
pub mod smooth;
pub mod trig;
