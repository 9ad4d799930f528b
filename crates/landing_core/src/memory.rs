//! How much memory a request may take, asked before anything is allocated.
//!
//! A batch's buffers are sized up front; on Linux the kernel hands out virtual memory freely
//! and only kills the process when the pages are touched, so a request that cannot fit must be
//! refused by comparing its size with what the machine has left, not by a failed allocation.

/// Bytes this process can still take: the kernel's estimate of available memory
/// (`MemAvailable` in /proc/meminfo), or the room left under the cgroup's memory limit when
/// that is smaller (containers, CI runners). `None` where neither can be read (other systems):
/// the allocations are then fallible and refused only if they fail.
pub fn available_bytes() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| parse_meminfo(&s));
    let cgroup = cgroup_room();
    match (meminfo, cgroup) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// `MemAvailable` in bytes.
fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The cgroup v2 limit minus current usage, if the process runs under a limit.
fn cgroup_room() -> Option<u64> {
    let max = std::fs::read_to_string("/sys/fs/cgroup/memory.max").ok()?;
    let max: u64 = max.trim().parse().ok()?; // "max" (no limit) does not parse
    let current: u64 = std::fs::read_to_string("/sys/fs/cgroup/memory.current")
        .ok()?
        .trim()
        .parse()
        .ok()?;
    Some(max.saturating_sub(current))
}

/// `bytes` in GiB, for messages.
pub fn gib(bytes: u128) -> f64 {
    bytes as f64 / (1u64 << 30) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_mem_available() {
        let text = "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   12345 kB\n";
        assert_eq!(parse_meminfo(text), Some(12345 * 1024));
        assert_eq!(parse_meminfo("MemTotal: 1 kB\n"), None);
    }

    #[test]
    fn this_machine_reports_some_memory() {
        if cfg!(target_os = "linux") {
            let a = available_bytes().expect("Linux has /proc/meminfo");
            assert!(a > 1 << 20, "{a} bytes available");
        }
    }
}
