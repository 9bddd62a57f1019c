//! The text of Slurm batch scripts: `#SBATCH` directives (the time and memory of the cost
//! estimate unless the user's `--sbatch-arg` gives them) and a body of shell lines. Pure.

/// The first comment line of every script settle writes: settle replaces only files that begin
/// with it.
pub const MARK: &str = "# Written by settle";

/// What one task asks of the scheduler.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resources {
    /// Wall-time limit, s.
    pub time_s: f64,
    /// Memory, bytes.
    pub mem_bytes: f64,
    /// CPUs.
    pub cpus: usize,
}

/// Safety factor on the estimated wall time: the estimate is measured on a 2-core laptop-class
/// machine and rounded up; a cluster core may be slower and a shared filesystem adds latency.
pub const TIME_FACTOR: f64 = 3.0;
/// Shortest wall time requested, s: start-up, file system and scheduling slack.
pub const MIN_TIME_S: f64 = 300.0;
/// Memory of the process besides the estimate (binary, allocator, tables), bytes.
pub const BASE_MEM_BYTES: f64 = 200e6;
/// Safety factor on the estimated memory.
pub const MEM_FACTOR: f64 = 1.5;

impl Resources {
    /// The request for a task whose estimate is `wall_s` of CPU time over `cpus` CPUs and
    /// `mem_bytes` of memory: wall × [`TIME_FACTOR`] (at least [`MIN_TIME_S`]), memory ×
    /// [`MEM_FACTOR`] + [`BASE_MEM_BYTES`].
    pub fn from_estimate(wall_s: f64, mem_bytes: f64, cpus: usize) -> Self {
        Self {
            time_s: (wall_s * TIME_FACTOR / cpus.max(1) as f64).max(MIN_TIME_S),
            mem_bytes: mem_bytes * MEM_FACTOR + BASE_MEM_BYTES,
            cpus: cpus.max(1),
        }
    }
}

/// A wall time as Slurm's `--time` takes it: `D-HH:MM:SS`, rounded up to the minute.
pub fn time_limit(s: f64) -> String {
    let min = (s / 60.0).ceil().max(1.0) as u64;
    let (d, h, m) = (min / 1440, (min / 60) % 24, min % 60);
    if d > 0 {
        format!("{d}-{h:02}:{m:02}:00")
    } else {
        format!("{h:02}:{m:02}:00")
    }
}

/// Memory as Slurm's `--mem` takes it: whole MB, rounded up.
pub fn mem(bytes: f64) -> String {
    format!("{}M", (bytes / 1e6).ceil().max(1.0) as u64)
}

/// Whether the user's sbatch options already set `option` (long form `--time`, short `-t`).
fn given(user: &[String], long: &str, short: &str) -> bool {
    user.iter().any(|a| {
        a == long
            || a.starts_with(&format!("{long}="))
            || a.starts_with(&format!("{long} "))
            || a.starts_with(short)
    })
}

/// The directives of a task: `--time`, `--mem`, `--cpus-per-task` from `r` unless the user's
/// options give them, then the user's options.
pub fn directives(r: &Resources, user: &[String]) -> Vec<String> {
    let mut d = Vec::new();
    if !given(user, "--time", "-t") {
        d.push(format!("--time={}", time_limit(r.time_s)));
    }
    if !given(user, "--mem", "--mem-per-cpu") {
        d.push(format!("--mem={}", mem(r.mem_bytes)));
    }
    if !given(user, "--cpus-per-task", "-c") {
        d.push(format!("--cpus-per-task={}", r.cpus));
    }
    d.extend(user.iter().cloned());
    d
}

/// A batch script: what it does (a comment), its directives and its shell lines.
pub fn render(what: &str, directives: &[String], body: &[String]) -> String {
    let mut s = format!(
        "#!/bin/bash\n{MARK} {}: {what}.\n# Edit the #SBATCH lines freely; settle rewrites this file when it submits again.\n",
        env!("CARGO_PKG_VERSION")
    );
    for d in directives {
        s.push_str(&format!("#SBATCH {d}\n"));
    }
    s.push('\n');
    for l in body {
        s.push_str(l);
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_round_up() {
        assert_eq!(time_limit(1.0), "00:01:00");
        assert_eq!(time_limit(61.0), "00:02:00");
        assert_eq!(time_limit(3600.0 * 25.0 + 1.0), "1-01:01:00");
        assert_eq!(mem(1.5e6), "2M");
        let r = Resources::from_estimate(1000.0, 1e9, 2);
        assert_eq!(r.time_s, 1500.0);
        assert_eq!(r.mem_bytes, 1.7e9);
        assert_eq!(Resources::from_estimate(1.0, 0.0, 1).time_s, MIN_TIME_S);
    }

    #[test]
    fn the_users_options_win() {
        let r = Resources::from_estimate(10.0, 1e6, 1);
        let d = directives(&r, &["--time=2:00:00".into(), "-p debug".into()]);
        assert_eq!(d.iter().filter(|x| x.starts_with("--time")).count(), 1);
        assert!(d.contains(&"--time=2:00:00".to_string()), "{d:?}");
        assert!(d.iter().any(|x| x.starts_with("--mem=")), "{d:?}");
        let s = render("a test", &d, &["echo hi".into()]);
        assert!(s.starts_with("#!/bin/bash\n# Written by settle"), "{s}");
        assert!(
            s.contains("#SBATCH -p debug\n") && s.ends_with("echo hi\n"),
            "{s}"
        );
    }
}
