//! `klaw scenario`: a good file writes its frames; a bad one exits 2 naming the action and the
//! field, and writes nothing.
use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("klaw-scenario-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn klaw(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn an_example_writes_its_frames() {
    let d = dir("good");
    let out = d.join("spin.csv");
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenarios/spin.toml");
    let (code, err) = klaw(&[
        "scenario",
        file,
        "--out",
        out.to_str().unwrap(),
        "--fps",
        "50",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    // a header and one row per frame: 5.5 s at 50 frames/s
    assert_eq!(text.lines().count(), 1 + 276);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_files_exit_2_and_write_nothing() {
    let d = dir("bad");
    for (text, want) in [
        (
            "[[action]]\ntype = \"jump\"\n",
            "action 0 (jump, from 0), `type`",
        ),
        (
            "[[action]]\ntype = \"stand\"\n[[action]]\ntype = \"step\"\nside = \"right\"\nleft = 0.5\n",
            "action 1 (step)",
        ),
        (
            "[[action]]\ntype = \"turn\"\nside = \"left\"\nkind = \"dynamic\"\n",
            "angle",
        ),
    ] {
        let file = d.join("s.toml");
        std::fs::write(&file, text).unwrap();
        let out = d.join("s.csv");
        let (code, err) = klaw(&[
            "scenario",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{text}: {err}");
        assert!(err.contains(want), "{err} should name {want}");
        assert!(!out.exists(), "nothing written");
    }
    std::fs::remove_dir_all(&d).unwrap();
}
