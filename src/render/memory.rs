//! How much memory a render needs beyond what its scene already holds,
//! and how much the machine has: checked before the film is allocated, so
//! a render that cannot finish is refused before its first sample, not
//! aborted after its last (docs/farm.md, "Memory").

/// Bytes a pixel of a film takes: an f64 sum of each channel and a count.
pub const FILM_BYTES_PER_PIXEL: u64 = 3 * 8 + 4;
/// Bytes the half images add to a pixel of the film: the f64 sum of its
/// odd samples' channels and whether adaptive sampling stopped it.
pub const HALVES_BYTES_PER_PIXEL: u64 = 3 * 8 + 1;
/// Memory the writers of images and states use at most beyond the film
/// (rows, blocks and buffers in flight), and the render's per-thread work.
pub const WORKING_BYTES: u64 = 64 << 20;

/// What a render needs: its film and working memory (still to be
/// allocated), and what its scene already holds (textures and geometry,
/// loaded), for the user's information.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Need {
    /// Width and height of the film.
    pub size: (u32, u32),
    /// Bytes of the film.
    pub film: u64,
    /// Bytes of the textures and environment maps, already loaded.
    pub textures: u64,
    /// Bytes of the AOVs written with the image (their per-pixel
    /// surfaces, planes, and the copies the EXR writer takes).
    pub aovs: u64,
}

impl Need {
    /// A film of `(width, height)` pixels.
    pub fn film(size: (u32, u32)) -> Need {
        Need {
            size,
            film: size.0 as u64 * size.1 as u64 * FILM_BYTES_PER_PIXEL,
            textures: 0,
            aovs: 0,
        }
    }

    /// With the half images (of adaptive sampling, or for the variance
    /// AOV), if `halves`.
    pub fn with_halves(self, halves: bool) -> Need {
        let pixels = self.size.0 as u64 * self.size.1 as u64;
        let extra = if halves {
            pixels * HALVES_BYTES_PER_PIXEL
        } else {
            0
        };
        Need {
            film: self.film + extra,
            ..self
        }
    }

    /// With the light film of an integrator that splats (`bdpt`, `ptlt`):
    /// a sum per pixel, 24 bytes, if `light`.
    pub fn with_light(self, light: bool) -> Need {
        let pixels = self.size.0 as u64 * self.size.1 as u64;
        Need {
            film: self.film + if light { pixels * 24 } else { 0 },
            ..self
        }
    }

    /// With AOVs of `channels` channels in all: per pixel the surface
    /// found (48 bytes), the colour copied for the writer (12) and each
    /// channel's plane twice (ours and the writer's, 4 bytes each).
    pub fn with_aovs(self, channels: u32) -> Need {
        let pixels = self.size.0 as u64 * self.size.1 as u64;
        let aovs = match channels {
            0 => 0,
            c => pixels * (48 + 12 + 8 * c as u64),
        };
        Need { aovs, ..self }
    }

    /// Bytes still to be allocated: the film and the working memory.
    pub fn to_allocate(&self) -> u64 {
        self.film + self.aovs + WORKING_BYTES
    }

    /// "film 8192×8192 1.88 GB, writing 0.07 GB, textures 0.01 GB (loaded)".
    pub fn describe(&self) -> String {
        let (w, h) = self.size;
        let mut text = format!(
            "film {w}×{h} {}, working memory {}",
            gigabytes(self.film),
            gigabytes(WORKING_BYTES)
        );
        if self.aovs > 0 {
            text.push_str(&format!(", AOVs {}", gigabytes(self.aovs)));
        }
        if self.textures > 0 {
            text.push_str(&format!(", textures {} (loaded)", gigabytes(self.textures)));
        }
        text
    }
}

/// Bytes in GB with two decimals (10^9 bytes, as `free -g` does not, but
/// as disks and `--memory-limit` do).
pub fn gigabytes(bytes: u64) -> String {
    format!("{:.2} GB", bytes as f64 / 1e9)
}

/// Memory still free to this process, and which limit says so: the
/// smallest of the machine's available memory, its control group's limit
/// and its address-space limit (`ulimit -v`), or, given `limit` (the whole
/// process's, `--memory-limit`), that less what the process holds now.
/// None where the system tells nothing.
pub fn available(limit: Option<u64>) -> Option<(u64, String)> {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    if let Some(limit) = limit {
        let held = status_bytes(&status, "VmRSS:").unwrap_or(0);
        return Some((limit.saturating_sub(held), "--memory-limit".into()));
    }
    let read = |path: &str| std::fs::read_to_string(path).unwrap_or_default();
    let mut found: Vec<(u64, String)> = Vec::new();
    if let Some(free) = status_bytes(&read("/proc/meminfo"), "MemAvailable:") {
        found.push((free, "the machine's available memory".into()));
    }
    if let Some(free) = cgroup_free(&read("/proc/self/cgroup"), &read) {
        found.push((free, "its control group's memory limit".into()));
    }
    if let (Some(limit), Some(size)) = (
        address_space_limit(&read("/proc/self/limits")),
        status_bytes(&status, "VmSize:"),
    ) {
        let why = "the address-space limit (ulimit -v)".into();
        found.push((limit.saturating_sub(size), why));
    }
    found.into_iter().min_by_key(|(bytes, _)| *bytes)
}

/// Refuses a render whose film and working memory exceed what is
/// [`available`] (`limit`: `--memory-limit`), saying how much it needs.
pub fn check(need: &Need, limit: Option<u64>) -> Result<(), String> {
    let Some((free, which)) = available(limit) else {
        return Ok(());
    };
    if need.to_allocate() <= free {
        return Ok(());
    }
    // Lowering the resolution helps only where the film is what is large.
    let advice = if need.film + need.aovs > WORKING_BYTES {
        "lower the resolution, or give --memory-limit if the memory is there"
    } else {
        "the loaded scene holds the rest: give a higher --memory-limit if the memory is there"
    };
    Err(format!(
        "this render needs {} of memory ({}), more than the {} free ({which}); {advice}",
        gigabytes(need.to_allocate()),
        need.describe(),
        gigabytes(free),
    ))
}

/// A `Key:   N kB` line of /proc/meminfo or /proc/self/status, in bytes.
fn status_bytes(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line[key.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib * 1024)
}

/// The soft "Max address space" of /proc/self/limits, if limited.
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// What the process's control group (v2, or v1's memory controller) has
/// left under its limit, if it has one; `read` reads a file.
fn cgroup_free(cgroup: &str, read: &dyn Fn(&str) -> String) -> Option<u64> {
    let number = |text: String| text.trim().parse::<u64>().ok();
    if let Some(path) = cgroup.lines().find_map(|l| l.strip_prefix("0::")) {
        let dir = format!("/sys/fs/cgroup{}", path.trim_end_matches('/'));
        let max = number(read(&format!("{dir}/memory.max")))?;
        let used = number(read(&format!("{dir}/memory.current"))).unwrap_or(0);
        return Some(max.saturating_sub(used));
    }
    let path = cgroup.lines().find_map(|l| {
        let (_, rest) = l.split_once(':')?;
        let (controllers, path) = rest.split_once(':')?;
        controllers
            .split(',')
            .any(|c| c == "memory")
            .then_some(path)
    })?;
    let dir = format!("/sys/fs/cgroup/memory{}", path.trim_end_matches('/'));
    let max = number(read(&format!("{dir}/memory.limit_in_bytes")))?;
    // v1 says "no limit" with a number near 2^63.
    if max >= 1 << 60 {
        return None;
    }
    let used = number(read(&format!("{dir}/memory.usage_in_bytes"))).unwrap_or(0);
    Some(max.saturating_sub(used))
}

/// A size as `--memory-limit` takes it: bytes, or a number with K, M, G or
/// T (powers of 1000; KiB, MiB, GiB, TiB for powers of 1024), e.g. `16G`,
/// `2.5GB`, `512MiB`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale: f64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "m" | "mb" => 1e6,
        "g" | "gb" => 1e9,
        "t" | "tb" => 1e12,
        "kib" => 1024.0,
        "mib" => 1024f64.powi(2),
        "gib" => 1024f64.powi(3),
        "tib" => 1024f64.powi(4),
        _ => {
            return Err(format!(
                "`{text}` is not a size such as 16G, 2.5GB or 512MiB"
            ))
        }
    };
    let bytes = (number.parse::<f64>().ok())
        .map(|n| n * scale)
        .filter(|b| (1e6..=1e15).contains(b))
        .ok_or_else(|| format!("`{text}` is not a size from 1M to 1000T (e.g. 16G)"))?;
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_in_decimal_and_binary_units() {
        assert_eq!(parse_size("16G"), Ok(16_000_000_000));
        assert_eq!(parse_size("2.5GB"), Ok(2_500_000_000));
        assert_eq!(parse_size("512MiB"), Ok(512 << 20));
        assert_eq!(parse_size("3000000"), Ok(3_000_000));
        for bad in ["", "G", "12X", "1k", "-5G", "1e20"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn limits_are_read_from_procs_files() {
        assert_eq!(
            status_bytes("MemAvailable:   2048 kB\n", "MemAvailable:"),
            Some(2 << 20)
        );
        let limits = "Max stack size            8388608              unlimited            bytes\nMax address space         3000000000           unlimited            bytes\n";
        assert_eq!(address_space_limit(limits), Some(3_000_000_000));
        let unlimited =
            "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_space_limit(unlimited), None);
        let files = |path: &str| match path {
            "/sys/fs/cgroup/job/memory.max" => "4000000000\n".to_string(),
            "/sys/fs/cgroup/job/memory.current" => "1000000000\n".to_string(),
            _ => String::new(),
        };
        assert_eq!(cgroup_free("0::/job\n", &files), Some(3_000_000_000));
        let open = |_: &str| "max\n".to_string();
        assert_eq!(cgroup_free("0::/\n", &open), None);
    }

    #[test]
    fn a_film_larger_than_the_limit_is_refused_with_its_size() {
        let need = Need::film((8192, 8192));
        assert_eq!(need.film, 8192 * 8192 * 28);
        let why = check(&need, Some(1_000_000_000)).unwrap_err();
        assert!(
            why.contains("needs 1.95 GB") && why.contains("film 8192×8192 1.88 GB"),
            "{why}"
        );
        assert_eq!(check(&Need::film((64, 64)), Some(1 << 40)), Ok(()));
        // Adaptive sampling's half images: 25 bytes more a pixel.
        let halves = Need::film((8192, 8192)).with_halves(true);
        assert_eq!(halves.film, 8192 * 8192 * (28 + 25));
        let why = check(&halves, Some(3_000_000_000)).unwrap_err();
        assert!(why.contains("film 8192×8192 3.56 GB"), "{why}");
        assert_eq!(Need::film((8, 8)).with_halves(false), Need::film((8, 8)));
    }
}
