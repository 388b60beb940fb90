//! The bash completion script, run by bash: options and their values complete.

use std::process::Command;

use crate::support::bin;

/// What bash's completion function offers for the words `line` (the last one being typed).
fn complete(script: &str, line: &[&str]) -> Vec<String> {
    let words: Vec<String> = line.iter().map(|w| format!("'{w}'")).collect();
    let program = format!(
        "{script}\nCOMP_WORDS=({words})\nCOMP_CWORD=$((${{#COMP_WORDS[@]}} - 1))\nCOMPREPLY=()\n_vrep__maze vrep-maze \"${{COMP_WORDS[COMP_CWORD]}}\" \"${{COMP_WORDS[COMP_CWORD-1]}}\"\nprintf '%s\\n' \"${{COMPREPLY[@]}}\"\n",
        words = words.join(" ")
    );
    let out = Command::new("bash")
        .arg("-c")
        .arg(program)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter(|l| !l.is_empty())
        .map(str::to_string)
        .collect()
}

#[test]
fn bash_completes_subcommands_options_and_their_values() {
    let script = String::from_utf8(
        bin()
            .args(["completions", "bash"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone(),
    )
    .unwrap();
    let c = |line: &[&str]| complete(&script, line);
    assert!(c(&["vrep-maze", "so"]).contains(&"solve".to_string()));
    assert_eq!(c(&["vrep-maze", "generate", "--al"]), ["--algo"]);
    let algorithms = c(&["vrep-maze", "generate", "--algo", ""]);
    assert!(
        algorithms.contains(&"prim".into()) && algorithms.contains(&"recursive-division".into()),
        "{algorithms:?}"
    );
    assert_eq!(
        c(&["vrep-maze", "batch", "--style", ""]),
        ["lines", "walls"]
    );
    assert_eq!(
        c(&["vrep-maze", "render", "m.json", "--format", "s"]),
        ["svg"]
    );
    assert_eq!(c(&["vrep-maze", "apply", "m.json", "--api", "z"]), ["zmq"]);
    assert_eq!(
        c(&["vrep-maze", "solve", "m.json", "--format", ""]),
        ["json", "csv"]
    );
    assert!(c(&["vrep-maze", "inspect", "--la"]).contains(&"--layout".to_string()));
    // Options parsed from text list their values too, forms with a parameter as a hint.
    assert_eq!(
        c(&["vrep-maze", "generate", "--growing", ""]),
        ["newest", "oldest", "random", "middle", "mix:P"]
    );
    assert_eq!(
        c(&["vrep-maze", "batch", "--growing", "m"]),
        ["middle", "mix:P"]
    );
    assert_eq!(c(&["vrep-maze", "generate", "--bias", "n"]), ["ne", "nw"]);
    assert_eq!(
        c(&["vrep-maze", "generate", "--start", "f"]),
        ["farthest-pair"]
    );
    assert_eq!(c(&["vrep-maze", "generate", "--end", "f"]), ["farthest"]);
    assert_eq!(
        c(&["vrep-maze", "generate", "--openings", "s"]),
        ["start", "start,end"]
    );
    assert_eq!(
        c(&["vrep-maze", "generate", "--preset", ""]),
        ["micromouse", "micromouse-half"]
    );
    assert_eq!(c(&["vrep-maze", "demo", "--algo", "w"]), ["wilson"]);
    assert_eq!(
        c(&["vrep-maze", "export", "m.json", "--format", "u"]),
        ["urdf"]
    );
    assert_eq!(c(&["vrep-maze", "score", "--until", ""]), ["end", "stop"]);
}
