//! The charts of free-settling and drop runs read as issue 13 asks (title, axis labels with units,
//! ticks of at most 6 significant digits, legend outside the data), and show what they claim:
//! the analytic Stokes curve of the run's own constants (f-EDEM Figs. 5–6), Table 3's Re′–C_d
//! points with eq. 19 (Fig. 1), one parity chart of several files with ±10 % and ±25 % bands
//! (Figs. 9–11), and the drop's settling distance (Fig. 16); the measured v(t) and gap of ten
//! Cate et al. (2002) beside the simulated ones (`[reference]`, issue 16).

use crate::common::chart::{assert_readable_chart, tick_value};
use crate::common::{read_csv_records, settle, tmp};
use std::path::Path;

/// Runs `settle run` on `files` into `out` with `extra` arguments; panics on failure.
fn run(out: &Path, files: &[&str], extra: &[&str]) {
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(out)
        .args(files)
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Every `<text>` of the SVG at `path` with its `x` attribute (px) and its content (tags
/// removed, `&amp;` and the like left as written: the callers look for plain words).
fn text_xs(path: &Path) -> Vec<(f64, String)> {
    let svg = std::fs::read_to_string(path).unwrap();
    let mut out = Vec::new();
    let mut rest = svg.as_str();
    while let Some(k) = rest.find("<text") {
        rest = &rest[k..];
        let (Some(open), Some(close)) = (rest.find('>'), rest.find("</text>")) else {
            break;
        };
        let x = rest[..open]
            .split_once(" x=\"")
            .and_then(|(_, t)| t.split('"').next())
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(f64::NAN);
        let mut text = String::new();
        let mut in_tag = false;
        for c in rest[open + 1..close].chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                c if !in_tag => text.push(c),
                _ => {}
            }
        }
        out.push((x, text.trim().to_string()));
        rest = &rest[close + "</text>".len()..];
    }
    out
}

/// Issue 13: "the legend covers the curves". Every legend label (a text among `labels`) sits
/// right of every tick label of the x axis.
pub fn assert_legend_outside(path: &Path, labels: &[&str]) {
    let xs = text_xs(path);
    let rightmost_tick = xs
        .iter()
        .filter(|(_, t)| tick_value(t).is_some())
        .map(|(x, _)| *x)
        .fold(f64::MIN, f64::max);
    for l in labels {
        let (x, _) = xs
            .iter()
            .find(|(_, t)| t.contains(l))
            .unwrap_or_else(|| panic!("{}: no legend label `{l}`", path.display()));
        assert!(
            *x > rightmost_tick,
            "{}: legend label `{l}` at x = {x} is inside the data (last tick at {rightmost_tick})",
            path.display()
        );
    }
}

/// The number printed after `key` in `text`, up to the next space.
fn after(text: &str, key: &str) -> f64 {
    text.split(key)
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// f-EDEM Figs. 5–6: v(t) of the Stokes sphere with the analytic curve v_t (1 − e^(−t/τ)) of its
/// own constants: v_t = (ρ_p − ρ_f) g d²/(18 μ), τ = ρ_p d²/(18 μ) (no added mass in the code).
#[test]
fn stokes_velocity_chart_draws_the_analytic_curve_of_the_runs_own_constants() {
    let out = tmp();
    run(out.path(), &["scenarios/stokes_single.toml"], &[]);
    let svg = out.path().join("stokes_single/velocity.svg");
    let texts = assert_readable_chart(
        &svg,
        "stokes_single: settling velocity against time",
        &["time t (s)", "settling velocity v"],
    );
    let legend = texts.join(" ");
    assert!(legend.contains("analytic Stokes"), "{legend}");
    let (d, rho_p, rho_f, mu, g) = (1e-4, 2700.0, 1000.0, 1e-3, 9.81);
    let vt = (rho_p - rho_f) * g * d * d / (18.0 * mu);
    let tau = rho_p * d * d / (18.0 * mu);
    let (vt_drawn, tau_drawn) = (after(&legend, "v_t = "), after(&legend, "τ = "));
    assert!((vt_drawn / vt - 1.0).abs() < 1e-3, "{vt_drawn} vs {vt}");
    assert!((tau_drawn / tau - 1.0).abs() < 1e-3, "{tau_drawn} vs {tau}");
    assert_legend_outside(&svg, &["simulated", "analytic Stokes"]);
}

/// Issue 13: "a single sphere gets a y axis from 0.0042 to 0.00432 m/s". One measured sphere at
/// 0.0043 m/s: the axis starts at zero, its ticks stay coarse, the legend sits outside.
#[test]
fn a_single_measured_sphere_gets_a_sane_velocity_axis() {
    let out = tmp();
    run(
        out.path(),
        &["scenarios/stokes_single.toml"],
        &["--set", "spheres[0].v_measured_m_s=0.0043"],
    );
    let svg = out.path().join("stokes_single/terminal_velocity.svg");
    let texts = assert_readable_chart(
        &svg,
        "terminal velocity, measured (hollow) and simulated (filled)",
        &["sphere density (kg/m³)", "terminal velocity (m/s)"],
    );
    let ticks: Vec<f64> = texts.iter().filter_map(|t| tick_value(t)).collect();
    assert!(ticks.contains(&0.0), "no zero tick in {texts:?}");
    let top = ticks
        .iter()
        .copied()
        .filter(|v| *v < 0.1)
        .fold(0.0, f64::max);
    assert!(top < 0.02, "y ticks reach {top} in {texts:?}");
    assert_legend_outside(&svg, &["d = 0.1 mm, measured", "d = 0.1 mm, simulated"]);
}

/// f-EDEM Fig. 1 and Figs. 9–11: two Valentik suspensions in one run. Per file: the readable
/// terminal-velocity chart and the C_d–Re′ chart, whose measured points are Table 3's (Re′ within
/// 1.2 % of the tabulated, as the validation computes them) and whose simulated points lie on
/// eq. 19 away from its jumps; in OUT/combined/: the parity chart with its bands, the combined
/// terminal-velocity and C_d–Re′ charts.
#[test]
fn valentik_charts_show_table_3_eq_19_and_one_parity_chart() {
    let out = tmp();
    let files = [
        "scenarios/valentik_susp1.toml",
        "scenarios/valentik_susp6.toml",
    ];
    run(out.path(), &files, &[]);
    let tab: Vec<_> = read_csv_records(Path::new("data/valentik_whitmore_1965_spheres.csv"));
    for name in ["valentik_susp1", "valentik_susp6"] {
        let dir = out.path().join(name);
        assert_readable_chart(
            &dir.join("terminal_velocity.svg"),
            "terminal velocity",
            &["sphere density (kg/m³)", "terminal velocity (m/s)"],
        );
        let svg = dir.join("cd_re.svg");
        assert_readable_chart(
            &svg,
            "drag coefficient against Bingham Reynolds number",
            &["Bingham Reynolds number Re′", "drag coefficient C_d"],
        );
        assert_legend_outside(&svg, &["measured velocities", "simulated", "eq. 19"]);
        let rows = read_csv_records(&dir.join("cd_re.csv"));
        assert!(!rows.is_empty());
        let mut on_curve = 0;
        for r in &rows {
            let t = tab
                .iter()
                .find(|t| t["sphere_id"] == r["sphere_id"])
                .unwrap();
            let re: f64 = r["re_bingham_measured"].parse().unwrap();
            let re_tab: f64 = t["re_bingham_tabulated"].parse().unwrap();
            assert!((re / re_tab - 1.0).abs() < 0.012 + 0.05 / re_tab, "{r:?}");
            let (Ok(re_sim), Ok(cd), Ok(eq19)) = (
                r["re_bingham_simulated"].parse::<f64>(),
                r["cd_simulated"].parse::<f64>(),
                r["cd_eq19_at_simulated"].parse::<f64>(),
            ) else {
                continue;
            };
            let at_jump = [1.0, 150.0].iter().any(|j| (re_sim / j - 1.0).abs() < 1e-3);
            if !at_jump {
                assert!((cd / eq19 - 1.0).abs() < 1e-3, "{r:?}");
                on_curve += 1;
            }
        }
        assert!(on_curve > rows.len() / 2, "{on_curve} of {}", rows.len());
    }
    let combined = out.path().join("combined");
    let parity = combined.join("parity.svg");
    let texts = assert_readable_chart(
        &parity,
        "simulated against measured terminal velocity",
        &[
            "measured terminal velocity (m/s)",
            "simulated terminal velocity (m/s)",
        ],
    );
    for label in [
        "within ±10 %",
        "within ±25 %",
        "parity",
        "suspension 1",
        "suspension 6",
    ] {
        assert!(
            texts.iter().any(|t| t.contains(label)),
            "{label} in {texts:?}"
        );
    }
    assert_legend_outside(&parity, &["within ±10 %", "suspension 1 ("]);
    assert_readable_chart(
        &combined.join("terminal_velocity.svg"),
        "terminal velocity",
        &["sphere density (kg/m³)", "terminal velocity (m/s)"],
    );
    assert_readable_chart(
        &combined.join("cd_re.svg"),
        "drag coefficient",
        &["Re′", "C_d"],
    );
    let n = |f: &str| read_csv_records(&out.path().join(f)).len();
    assert_eq!(
        n("combined/cd_re.csv"),
        n("valentik_susp1/cd_re.csv") + n("valentik_susp6/cd_re.csv")
    );
}

/// f-EDEM Fig. 16 and the drop's v(t): settling distance against fall height, readable.
#[test]
fn drop_charts_are_readable() {
    let out = tmp();
    run(out.path(), &["scenarios/paste_single_ball.toml"], &[]);
    let dir = out.path().join("paste_single_ball");
    let svg = dir.join("settling_distance.svg");
    assert_readable_chart(
        &svg,
        "settling distance against fall height",
        &["fall height (mm)", "settling distance"],
    );
    assert_legend_outside(&svg, &["d = 8 mm", "d = 16 mm"]);
    assert_readable_chart(
        &dir.join("velocity.svg"),
        "settling velocity against time",
        &["time t (s)", "settling velocity v"],
    );
}

/// The `[reference]` of ten Cate E1 (the digitised Fig. 5 of ten Cate et al. 2002): `velocity.svg`
/// and `gap.svg` show every measured point as a hollow marker (one polyline per marker in the
/// series' colour, plus its legend sample) under a legend entry naming the source, and read as
/// issue 13 asks.
#[test]
fn ten_cate_charts_overlay_the_measured_curves() {
    let out = tmp();
    run(out.path(), &["scenarios/ten_cate_e1.toml"], &[]);
    let dir = out.path().join("ten_cate_e1");
    let rows = |f: &str| read_csv_records(Path::new(&format!("data/ten_cate_2002/{f}"))).len();
    for (svg, title, y, n) in [
        (
            "velocity.svg",
            "settling velocity against time",
            "settling velocity v",
            rows("ten_cate_e1_velocity.csv"),
        ),
        (
            "gap.svg",
            "gap between sphere and bottom against time",
            "gap between sphere and bottom (m)",
            rows("ten_cate_e1_gap.csv"),
        ),
    ] {
        let path = dir.join(svg);
        let texts = assert_readable_chart(&path, title, &["time t (s)", y]);
        let label = format!("measured ({n} points): ten Cate et al. (2002)");
        assert!(
            texts.iter().any(|t| t.contains(&label)),
            "{svg}: `{label}` in {texts:?}"
        );
        assert!(texts.iter().any(|t| t.contains("nylon-15mm, simulated")));
        // The measured series takes the second colour (orange, #FF7F0E), hollow squares.
        let text = std::fs::read_to_string(&path).unwrap();
        let markers = text
            .lines()
            .filter(|l| l.starts_with("<polyline") && l.contains("stroke=\"#FF7F0E\""))
            .count();
        assert_eq!(
            markers,
            n + 1,
            "{svg}: {n} measured markers and the legend's"
        );
    }
    // Without the table: no measured series, no gap chart.
    let bare = tmp();
    let toml = bare.path().join("e1.toml");
    let text = std::fs::read_to_string("scenarios/ten_cate_e1.toml").unwrap();
    let cut = text.find("[reference]").unwrap();
    std::fs::write(&toml, &text[..cut]).unwrap();
    run(
        bare.path(),
        &[toml.to_str().unwrap()],
        &["--set", "time.end_s=0.5"],
    );
    let dir = bare.path().join("ten_cate_e1");
    assert!(!dir.join("gap.svg").exists());
    let texts = crate::common::chart::svg_texts(&dir.join("velocity.svg"));
    assert!(!texts.iter().any(|t| t.contains("measured")), "{texts:?}");
}
