//! The README's command lines work as written: every line of its ```sh blocks that starts with
//! `klaw ` runs, in order, in a fresh folder laid out like the clone's root (its `examples/` and
//! `models/` linked in, so that the shipped inputs are where the README names them and the
//! outputs land in the folder), and exits 0 — or with the status a trailing comment names
//! (`# exits 2`). Lines are split as a shell splits words, without quotes or globs, which the
//! README's commands do not use. And `klaw --help` names every subcommand.
use std::path::Path;
use std::process::Command;

/// The README's `klaw` command lines, with the exit status each expects.
fn readme_commands() -> Vec<(String, i32)> {
    let readme = include_str!("../README.md");
    let mut commands = Vec::new();
    let mut in_sh = false;
    for line in readme.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            in_sh = !in_sh && t == "```sh";
            continue;
        }
        if !in_sh || !t.starts_with("klaw ") {
            continue;
        }
        let (command, comment) = match t.find(" #") {
            Some(i) => (t[..i].trim(), &t[i + 2..]),
            None => (t, ""),
        };
        let status = comment
            .split("exits ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|s| s.parse().ok())
            .unwrap_or(0);
        commands.push((command.to_string(), status));
    }
    commands
}

#[test]
fn the_readmes_commands_run_as_written() {
    let commands = readme_commands();
    assert!(
        commands.len() >= 10,
        "{} klaw lines in README.md",
        commands.len()
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    for shipped in ["examples", "models"] {
        std::os::unix::fs::symlink(root.join(shipped), dir.path().join(shipped)).unwrap();
    }
    for (command, status) in &commands {
        let words: Vec<&str> = command.split_whitespace().skip(1).collect();
        assert!(
            !command.contains(['"', '\'', '*', '$', '|', '>', '<']),
            "README: `{command}`: no quotes, globs, variables or redirections in a tested line"
        );
        let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args(&words)
            .current_dir(dir.path())
            .output()
            .expect("the klaw binary runs");
        assert_eq!(
            out.status.code(),
            Some(*status),
            "README: `{command}`:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// `klaw --help` names every subcommand in its description, as `klaw NAME`.
#[test]
fn the_help_names_every_command() {
    let help = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args(args)
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap()
    };
    let long = help(&["--help"]);
    let listed: Vec<String> = long
        .split("Commands:")
        .nth(1)
        .expect("a command list")
        .lines()
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .filter(|name| name != "help")
        .collect();
    assert!(listed.len() >= 15, "{listed:?}");
    let about = long.split("Commands:").next().unwrap();
    for name in &listed {
        assert!(
            about.contains(&format!("`klaw {name}")),
            "`klaw --help` does not describe `klaw {name}`"
        );
    }
}
