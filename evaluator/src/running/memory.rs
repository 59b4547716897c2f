//! Peak resident memory of the evaluator process, per run: Linux lets a process reset its
//! high-water mark (`/proc/self/clear_refs`), so each method's peak is measured on its own.
//! Elsewhere both functions do nothing and the timings table leaves the column empty.

/// Resets the process's peak resident set size to its current size (Linux only).
pub fn reset_peak() {
    // Writing 5 to clear_refs resets VmHWM (Linux >= 4.0); a failure only loses the figure.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// The process's peak resident set size since the last reset, in MiB, if known.
pub fn peak_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}
