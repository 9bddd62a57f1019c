//! The sections of a report page drawn from a run's record (`run.toml`): its warnings, its
//! record and its effective scenario.

use super::esc;
use crate::io::fmt::sig_trim;
use std::fmt::Write as _;

/// The effective scenario recorded in `run.toml`: its `[scenario]` table, or (a run.toml written
/// as a scenario file with a `[run]` record) everything but `[run]` and `[engine_settings]`.
pub(super) fn scenario_table(t: &toml::Table) -> toml::Table {
    if let Some(s) = t.get("scenario").and_then(|s| s.as_table()) {
        return s.clone();
    }
    t.iter()
        .filter(|(k, _)| !matches!(k.as_str(), "run" | "engine_settings"))
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}

/// A CSS class name from a status word (letters only).
pub(super) fn class_name(s: &str) -> String {
    s.chars().filter(|c| c.is_ascii_alphanumeric()).collect()
}

/// The run's validity warnings (`[run] warnings`), in a box that stands out, or "none".
pub(super) fn warnings_section(run: &toml::Table) -> String {
    let warnings = string_list(run.get("warnings"));
    let mut h = String::from("<section id=\"warnings\"><h2>Validity warnings</h2>");
    if warnings.is_empty() {
        h.push_str(
            "<div class=\"box ok\"><strong>none</strong>: every law was used within its \
             range as far as settle checks.</div>",
        );
    } else {
        let _ = write!(
            h,
            "<div class=\"box warn\"><strong>{} warning{}</strong> — read before using the \
             results:<ul>",
            warnings.len(),
            if warnings.len() == 1 { "" } else { "s" }
        );
        for w in &warnings {
            let _ = write!(h, "<li>{}</li>", esc(w));
        }
        h.push_str("</ul></div>");
    }
    h.push_str("</section>\n");
    h
}

/// The strings of a TOML array (other items written as TOML).
pub(super) fn string_list(v: Option<&toml::Value>) -> Vec<String> {
    v.and_then(|v| v.as_array())
        .map(|a| {
            a.iter()
                .map(|x| x.as_str().map_or_else(|| x.to_string(), str::to_string))
                .collect()
        })
        .unwrap_or_default()
}

/// A TOML value as a person reads it: floats to 4 significant digits, lists joined.
pub(super) fn value_text(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(f) => sig_trim(*f, 4),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Boolean(b) => if *b { "yes" } else { "no" }.to_string(),
        toml::Value::Array(a) if a.is_empty() => "none".to_string(),
        toml::Value::Array(a) => a.iter().map(value_text).collect::<Vec<_>>().join(", "),
        toml::Value::Table(t) if t.is_empty() => "none".to_string(),
        toml::Value::Table(t) => t
            .iter()
            .map(|(k, v)| format!("{k}: {}", value_text(v)))
            .collect::<Vec<_>>()
            .join("; "),
        other => other.to_string(),
    }
}

/// The run's record (`[run]` of run.toml but its warnings): status, engine, integrator, time
/// step, steps, bodies, wall time (the run's cost), settle version, then any other field.
pub(super) fn record_section(run: &toml::Table) -> String {
    const ORDER: &[&str] = &[
        "status",
        "engine",
        "integrator",
        "dt_s",
        "steps",
        "bodies",
        "wall_time_s",
        "settle_version",
        "scenario_file",
        "resumed",
    ];
    let mut keys: Vec<&str> = ORDER
        .iter()
        .copied()
        .filter(|k| run.contains_key(*k))
        .collect();
    keys.extend(
        run.keys()
            .map(String::as_str)
            .filter(|k| !ORDER.contains(k) && *k != "warnings"),
    );
    let mut h = String::from(
        "<section id=\"record\"><h2>Run record</h2>\
         <p class=\"note\">From <a href=\"run.toml\">run.toml</a>.</p><div class=\"kv\">",
    );
    for k in keys {
        let v = &run[k];
        let text = match k {
            "wall_time_s" => format!("{} s (the run's cost)", value_text(v)),
            "dt_s" => format!("{} s", value_text(v)),
            _ => value_text(v),
        };
        let _ = write!(
            h,
            "<div{}><span class=\"k\">{}</span><span class=\"v\">{}</span></div>",
            if text.chars().count() > 24 {
                " class=\"long\""
            } else {
                ""
            },
            esc(k),
            esc(&text)
        );
    }
    h.push_str("</div></section>\n");
    h
}

/// The effective scenario as TOML, folded.
pub(super) fn scenario_section(s: &toml::Table) -> String {
    let text = toml::to_string(s).unwrap_or_default();
    format!(
        "<section id=\"scenario\"><h2>Scenario</h2><details><summary>Effective scenario \
         (TOML, every default filled in)</summary><pre>{}</pre></details></section>\n",
        esc(&text)
    )
}
