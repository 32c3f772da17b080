//! A `VkPipelineCache` kept on disk, one file per device and driver: named by the device's
//! pipelineCacheUUID, vendor and device ids and driver version, so a driver update or another
//! GPU starts a new file. Read when the context opens, written back (atomically) when it
//! closes. A file that is damaged, foreign or from another driver is ignored, never handed to
//! the driver: its own header is checked against the device, and twinray's checksum against
//! the bytes.

use crate::error::{Error, Result, VkContext};
use crate::util::checksum::fnv1a;
use crate::util::input::read_bounded;
use crate::util::output::write_atomically;
use ash::vk;
use std::path::{Path, PathBuf};

/// The first bytes of a twinray pipeline cache file; then the data's length and its FNV-1a
/// (u64 each, little-endian), then the data as the driver gave it.
const MAGIC: &[u8; 8] = b"TWPCACH1";
/// Largest cache file read: a driver's cache of every twinray pipeline is a few MiB.
pub const MAX_CACHE_BYTES: u64 = 256 << 20;

/// An open pipeline cache and the file it goes back to.
pub struct PipelineCache {
    pub raw: vk::PipelineCache,
    pub file: PathBuf,
    /// Bytes of driver data it started from (0: cold).
    pub loaded_bytes: usize,
}

/// The cache file of the device `props` describes, in `dir`.
pub fn cache_file(dir: &Path, props: &vk::PhysicalDeviceProperties) -> PathBuf {
    let uuid: String = props.pipeline_cache_uuid.iter().map(|b| format!("{b:02x}")).collect();
    dir.join(format!("{uuid}-{:04x}-{:04x}-{:x}.pipelines", props.vendor_id, props.device_id, props.driver_version))
}

impl PipelineCache {
    /// A cache on `device` filled from `file` when it holds a valid cache of this device.
    pub fn open(device: &ash::Device, props: &vk::PhysicalDeviceProperties, file: PathBuf) -> Result<Self> {
        let data = read(&file, props).unwrap_or_default();
        let create = |data: &[u8]| {
            let info = vk::PipelineCacheCreateInfo::default().initial_data(data);
            // SAFETY: valid create info; destroyed with `destroy` before the device.
            unsafe { device.create_pipeline_cache(&info, None) }
        };
        // A driver may still refuse data it wrote: start cold then.
        let (raw, loaded_bytes) = match create(&data) {
            Ok(raw) => (raw, data.len()),
            Err(_) => (create(&[]).call("vkCreatePipelineCache")?, 0),
        };
        Ok(PipelineCache { raw, file, loaded_bytes })
    }

    /// Writes the cache's data back to its file, atomically.
    pub fn save(&self, device: &ash::Device) -> Result<()> {
        // SAFETY: the cache is live; no pipeline is being created from it now.
        let data = unsafe { device.get_pipeline_cache_data(self.raw) }.call("vkGetPipelineCacheData")?;
        if let Some(dir) = self.file.parent() {
            std::fs::create_dir_all(dir).map_err(|source| Error::Io { what: "creating", path: dir.into(), source })?;
        }
        let mut bytes = MAGIC.to_vec();
        bytes.extend((data.len() as u64).to_le_bytes());
        bytes.extend(fnv1a(&data).to_le_bytes());
        bytes.extend(data);
        write_atomically(&self.file, &bytes)
    }

    /// Destroys the cache; the device must outlive this call.
    pub fn destroy(&self, device: &ash::Device) {
        // SAFETY: no pipeline creation uses it any more.
        unsafe { device.destroy_pipeline_cache(self.raw, None) };
    }
}

/// The driver data of a cache file that twinray wrote for this very device and driver;
/// `None` for anything else (absent, short, damaged, another device's or driver's).
fn read(file: &Path, props: &vk::PhysicalDeviceProperties) -> Option<Vec<u8>> {
    let bytes = read_bounded(file, MAX_CACHE_BYTES).ok()?;
    let rest = bytes.strip_prefix(MAGIC.as_slice())?;
    let (len, rest) = rest.split_at_checked(8)?;
    let (sum, data) = rest.split_at_checked(8)?;
    let len = u64::from_le_bytes(len.try_into().ok()?);
    if len != data.len() as u64 || sum != fnv1a(data).to_le_bytes() {
        log::info!("ignoring the damaged pipeline cache {}", file.display());
        return None;
    }
    // Vulkan's own header: its length, version 1, vendor, device and cache UUID.
    let word = |i: usize| data.get(4 * i..4 * i + 4).and_then(|w| w.try_into().ok()).map(u32::from_le_bytes);
    let header_ok = word(0)? >= 32
        && word(1)? == vk::PipelineCacheHeaderVersion::ONE.as_raw() as u32
        && word(2)? == props.vendor_id
        && word(3)? == props.device_id
        && data.get(16..32)? == props.pipeline_cache_uuid.as_slice();
    if !header_ok {
        log::info!("ignoring the pipeline cache {}: written by another device or driver", file.display());
        return None;
    }
    Some(data.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn props() -> vk::PhysicalDeviceProperties {
        let mut p = vk::PhysicalDeviceProperties { vendor_id: 0x10de, device_id: 0x2330, ..Default::default() };
        p.pipeline_cache_uuid = [7; 16];
        p
    }

    /// A file as `save` writes it, around driver data with `header`.
    fn file_bytes(data: &[u8]) -> Vec<u8> {
        let mut bytes = MAGIC.to_vec();
        bytes.extend((data.len() as u64).to_le_bytes());
        bytes.extend(fnv1a(data).to_le_bytes());
        bytes.extend(data);
        bytes
    }

    fn driver_data(vendor: u32, uuid: [u8; 16]) -> Vec<u8> {
        let mut data = [32u32, 1, vendor, 0x2330].map(u32::to_le_bytes).concat();
        data.extend(uuid);
        data.extend(b"pipelines");
        data
    }

    #[test]
    fn only_intact_files_of_this_device_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.pipelines");
        let good = driver_data(0x10de, [7; 16]);
        std::fs::write(&path, file_bytes(&good)).unwrap();
        assert_eq!(read(&path, &props()), Some(good.clone()));
        let mut flipped = file_bytes(&good);
        *flipped.last_mut().unwrap() ^= 1;
        let cases = [
            ("a flipped bit", flipped),
            ("another vendor", file_bytes(&driver_data(0x1002, [7; 16]))),
            ("another driver's UUID", file_bytes(&driver_data(0x10de, [8; 16]))),
            ("truncated", file_bytes(&good)[..30].to_vec()),
            ("foreign", b"not a cache".to_vec()),
            ("empty", Vec::new()),
        ];
        for (what, bytes) in cases {
            std::fs::write(&path, bytes).unwrap();
            assert_eq!(read(&path, &props()), None, "{what}");
        }
        assert_eq!(read(&dir.path().join("absent"), &props()), None);
    }

    #[test]
    fn the_file_name_carries_the_device_and_driver() {
        let mut p = props();
        let a = cache_file(Path::new("d"), &p);
        p.driver_version += 1;
        assert_ne!(a, cache_file(Path::new("d"), &p));
        assert!(a.to_string_lossy().starts_with("d/07070707"), "{a:?}");
    }
}
