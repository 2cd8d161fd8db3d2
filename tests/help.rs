//! Every command's `--help` teaches by example: an `Examples:` section with at least one line
//! that runs the command itself. The commands are those `sweep --help` lists, so a new one is
//! held to it too.

use std::process::Command;

fn help(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run sweep");
    assert!(o.status.success(), "{args:?} failed");
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn every_command_has_examples_in_its_help() {
    let top = help(&["--help"]);
    let commands: Vec<String> = top
        .split("Commands:")
        .nth(1)
        .and_then(|t| t.split("Options:").next())
        .expect("a Commands section")
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .filter(|c| c != "help")
        .collect();
    assert!(commands.len() >= 12, "{commands:?}");
    for c in &commands {
        let help = help(&[c, "--help"]);
        let examples = help
            .split("Examples:")
            .nth(1)
            .unwrap_or_else(|| panic!("sweep {c} --help has no Examples section:\n{help}"));
        assert!(
            examples.contains(&format!("sweep {c} ")),
            "sweep {c} --help: no example runs the command:\n{examples}"
        );
    }
}
