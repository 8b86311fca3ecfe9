//! Numbers written as constant expressions (`t_end = "20*pi"`, `h = "2*pi/100"`,
//! `q = ["pi/2"]`): folded to the value the same arithmetic gives in Rust, and refused with a
//! caret when they name anything but constants.

use crate::util::marsden_in;

const TEXT: &str = "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [\"pi/2\"]\nv = [0]\n\
    [integrator]\nmethod = \"midpoint\"\nh = \"2*pi/100\"\nt_end = \"20*pi\"\n\
    [output]\nplots = false\nevery = 1000\n";

#[test]
fn constant_expressions_give_the_values_rust_computes() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("p.toml"), TEXT).unwrap();
    let r = marsden_in(tmp.path(), &["run", "p.toml", "--out", "o", "-q"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("o/summary.json")).unwrap())
            .unwrap();
    let pi = std::f64::consts::PI;
    assert_eq!(summary["h"].as_f64(), Some(2.0 * pi / 100.0));
    assert_eq!(
        summary["steps"].as_u64(),
        Some(1000),
        "t_end / h = 1000 steps"
    );
    let t = summary["final_state"]["t"].as_f64().unwrap();
    assert!((t - 20.0 * pi).abs() <= 1e-12 * t, "{t}");
    let rows = marsden_io::read_csv(tmp.path().join("o/trajectory.csv")).unwrap();
    assert_eq!(rows.values("q_theta").unwrap()[0], pi / 2.0);
}

#[test]
fn a_constant_expression_naming_an_unknown_symbol_is_refused_with_a_caret() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("p.toml"),
        TEXT.replace("2*pi/100", "2*pj/100"),
    )
    .unwrap();
    let r = marsden_in(tmp.path(), &["run", "p.toml", "--out", "o"]);
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("unknown name `pj`") && stderr.contains("did you mean `pi`"),
        "{stderr}"
    );
    assert!(stderr.contains("p.toml:8"), "{stderr}");
    assert!(stderr.contains('^'), "{stderr}");
    assert!(!tmp.path().join("o").exists());
}
