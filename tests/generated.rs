//! The tables klaw derives from its own engine are today's: each is regenerated here in memory
//! by the code of `cargo run --release --example regenerate -- models` and compared with the
//! committed file, so a change of the engine that makes one stale fails here (run that command
//! and review the diff). The bundled prototype's check is tests/generalize_cli.rs's
//! `the_bundled_prototype_is_the_default_walks`.
#[path = "../measure/generalize_fit.rs"]
mod generalize_fit;
#[path = "../measure/startup_fit.rs"]
mod startup_fit;

const REGENERATE: &str = "regenerate with `cargo run --release --example regenerate -- models`";

/// The start-up guesses (src/engine/startup.rs) are the fits of today's walks, started plainly
/// so that the fits do not depend on the file they replace: the same text, number for number.
#[test]
fn the_startup_guesses_are_todays() {
    let fresh = startup_fit::generate();
    let committed = include_str!("../models/startup-guesses.toml");
    for (i, (a, b)) in fresh.lines().zip(committed.lines()).enumerate() {
        assert_eq!(
            a,
            b,
            "models/startup-guesses.toml line {}: {REGENERATE}",
            i + 1
        );
    }
    assert_eq!(
        fresh.lines().count(),
        committed.lines().count(),
        "{REGENERATE}"
    );
}

/// The α slopes of models/generalize.toml (Ko & Badler 1992, eqs. 5, 6, 21, 24) are the
/// least-squares slopes of μ1…μ4 against sl / ll over today's walks, to the file's two decimals.
#[test]
fn the_alpha_slopes_are_todays() {
    let (walks, lines) = generalize_fit::fit().unwrap();
    assert!(walks > 50, "{walks} walks");
    let table = klaw::generalize::GeneralizeParameters::default().alphas();
    for ((name, line), alpha) in generalize_fit::NAMES.iter().zip(lines).zip(table) {
        let (fit, file) = (line.slope, alpha.to_degrees());
        assert!(
            (fit - file).abs() <= 0.005 + 1e-9,
            "{name}: the walks give α = {fit:.3}°/ll, models/generalize.toml {file:.3}: {REGENERATE}"
        );
    }
}
