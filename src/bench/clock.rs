//! Wall and process CPU time of a bench phase. On a machine shared with other
//! work the wall rate says little; the CPU time the phase got, spread over the
//! pool's threads, gives the rate those threads would reach alone (slightly
//! pessimistic: idle pool threads spinning count as work).

use std::time::Instant;

/// Ticks per second of `/proc/self/stat` times (`sysconf(_SC_CLK_TCK)`, 100 on Linux).
const CLOCK_TICKS_PER_S: f64 = 100.0;

/// User + system CPU seconds of this process so far (every thread), from
/// `/proc/self/stat`; `None` where that file does not exist.
pub fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    parse_cpu_seconds(&stat)
}

/// utime + stime (fields 14 and 15) of a `/proc/PID/stat` line, in seconds.
fn parse_cpu_seconds(stat: &str) -> Option<f64> {
    // The command name (field 2) may contain spaces: count from its ')'.
    let rest = &stat[stat.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(11);
    let utime: u64 = fields.next()?.parse().ok()?;
    let stime: u64 = fields.next()?.parse().ok()?;
    Some((utime + stime) as f64 / CLOCK_TICKS_PER_S)
}

/// A started measurement.
#[derive(Clone, Copy, Debug)]
pub struct Stopwatch {
    wall: Instant,
    cpu_s: Option<f64>,
}

/// How long a phase took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Span {
    /// Wall-clock seconds.
    pub wall_s: f64,
    /// Process CPU seconds (0 when unknown).
    pub cpu_s: f64,
}

impl Stopwatch {
    /// Starts measuring now.
    pub fn start() -> Stopwatch {
        Stopwatch {
            wall: Instant::now(),
            cpu_s: process_cpu_seconds(),
        }
    }

    /// Wall and CPU seconds since `start`.
    pub fn stop(&self) -> Span {
        let wall_s = self.wall.elapsed().as_secs_f64();
        let cpu_s = match (self.cpu_s, process_cpu_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => 0.0,
        };
        Span { wall_s, cpu_s }
    }
}

impl Span {
    /// Millions of `n` per wall second.
    pub fn wall_rate(&self, n: u64) -> f64 {
        n as f64 / self.wall_s.max(1e-9) / 1e6
    }

    /// Millions of `n` per second on `threads` threads that had the CPU to
    /// themselves: `n / (cpu_s / threads)`. Falls back to the wall rate when
    /// CPU time is unknown or the phase got more than `threads` CPUs.
    pub fn cpu_rate(&self, n: u64, threads: usize) -> f64 {
        let busy_s = self.cpu_s / threads.max(1) as f64;
        if busy_s <= 0.0 || busy_s >= self.wall_s {
            return self.wall_rate(n);
        }
        n as f64 / busy_s / 1e6
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_line_with_spaces_in_the_name_parses() {
        // pid (comm) state ppid pgrp session tty tpgid flags minflt cminflt majflt cmajflt utime stime ...
        let line = "4242 (my (odd) proc) R 1 2 3 4 5 6 7 8 9 10 250 75 0 0 20 0";
        assert_eq!(parse_cpu_seconds(line), Some(3.25));
        assert_eq!(parse_cpu_seconds("garbage"), None);
    }

    #[test]
    fn cpu_rate_scales_by_the_share_of_cpu_the_phase_got() {
        let span = Span {
            wall_s: 2.0,
            cpu_s: 2.0,
        };
        // Two threads got one CPU-second each in two wall seconds: half the machine.
        assert_eq!(span.wall_rate(4_000_000), 2.0);
        assert_eq!(span.cpu_rate(4_000_000, 2), 4.0);
        // More CPU than threads×wall (other threads busy): no scaling.
        let busy = Span {
            wall_s: 1.0,
            cpu_s: 3.0,
        };
        assert_eq!(busy.cpu_rate(1_000_000, 2), 1.0);
    }
}
