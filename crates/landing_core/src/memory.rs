//! How much memory a request may take, asked before anything is allocated.
//!
//! A batch's buffers are sized up front; on Linux the kernel hands out virtual memory freely
//! and only kills the process when the pages are touched, so a request that cannot fit must be
//! refused by comparing its size with what the machine has left, not by a failed allocation.

/// Bytes this process can still take: the kernel's estimate of available memory
/// (`MemAvailable` in /proc/meminfo), or less where a limit leaves less room: the cgroup's
/// memory limit (containers, CI runners) and the process's address-space limit (`ulimit -v`,
/// RLIMIT_AS, against its virtual size: beyond it an allocation fails however much memory is
/// free). `None` where none can be read (other systems): the allocations are then fallible and
/// refused only if they fail.
pub fn available_bytes() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| parse_meminfo(&s));
    [meminfo, cgroup_room(), address_space_room()]
        .into_iter()
        .flatten()
        .min()
}

/// The soft address-space limit (`Max address space` in /proc/self/limits) minus the
/// process's virtual size (`VmSize` in /proc/self/status); None when unlimited or unknown.
fn address_space_room() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let (limit, size) = (parse_address_limit(&limits)?, parse_vm_size(&status)?);
    Some(limit.saturating_sub(size))
}

/// The soft limit of `Max address space`, in bytes (None when "unlimited").
fn parse_address_limit(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// `VmSize` in bytes.
fn parse_vm_size(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("VmSize:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
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
    fn reads_the_address_space_limit_and_the_virtual_size() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units\n\
                      Max cpu time              unlimited            unlimited            seconds\n\
                      Max address space         4294967296           unlimited            bytes\n";
        assert_eq!(parse_address_limit(limits), Some(1 << 32));
        let open = limits.replace("4294967296 ", "unlimited  ");
        assert_eq!(parse_address_limit(&open), None);
        assert_eq!(
            parse_vm_size("Name: x\nVmSize:\t  2048 kB\n"),
            Some(2048 * 1024)
        );
    }

    #[test]
    fn this_machine_reports_some_memory() {
        if cfg!(target_os = "linux") {
            let a = available_bytes().expect("Linux has /proc/meminfo");
            assert!(a > 1 << 20, "{a} bytes available");
        }
    }
}
