//! The Vulkan context: instance, optional validation messenger, device, queue, allocator and
//! the ray tracing loaders. Everything else holds an `Arc<Context>`, so it is dropped last.

pub use super::device::DeviceInfo;
use super::device::{create_device, device_info, robustness, Robustness};
use super::device_select;
use super::kept::KeptPipelines;
use super::pipeline_cache::{cache_file, PipelineCache};
use super::validation::{self, Messenger, Validation, ValidationLog};
use crate::error::{Error, Result, VkContext};
use ash::{ext::debug_utils, khr, vk};
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme, Allocator, AllocatorCreateDesc};
use gpu_allocator::MemoryLocation;
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Options for [`Context::new`].
#[derive(Clone, Debug)]
pub struct ContextOptions {
    pub validation: Validation,
    /// Only devices whose name contains this (case-insensitive).
    pub device_filter: Option<String>,
    /// Folder of the on-disk pipeline caches (one file per device and driver); `None`: every
    /// pipeline is compiled cold and nothing is written.
    pub pipeline_cache: Option<std::path::PathBuf>,
    /// How ray tracing pipelines are made; `None`: from libraries where the device has
    /// VK_KHR_pipeline_library, else whole.
    pub pipelines: Option<PipelineKind>,
    /// Threads that join each pipeline creation (a deferred host operation); `None`: as many
    /// as the machine has cores.
    pub pipeline_threads: Option<usize>,
    /// How long one unit of GPU work (a trace, a build) and one pipeline creation may take
    /// before twinray gives up on it ([`DEFAULT_GPU_TIMEOUT`] unless asked otherwise).
    pub gpu_timeout: Duration,
    /// Turn on robust buffer and image access where the device has VK_EXT_robustness2 (see
    /// `device::Robustness`); off, a stray read gives whatever the driver gives.
    pub robust_access: bool,
    /// Let consecutive meshes placed alike share one bottom-level structure, each a geometry
    /// of it (`scene::merge`); off, every mesh is a structure of its own, as a check on the
    /// sharing or to bisect a difference to it.
    pub shared_blases: bool,
}

impl Default for ContextOptions {
    /// No validation, the first capable device, no pipeline cache, pipelines made as the
    /// device allows, one creation thread per core, [`DEFAULT_GPU_TIMEOUT`], robust access and
    /// shared BLASes on.
    fn default() -> Self {
        ContextOptions {
            validation: Validation::Off,
            device_filter: None,
            pipeline_cache: None,
            pipelines: None,
            pipeline_threads: None,
            gpu_timeout: DEFAULT_GPU_TIMEOUT,
            robust_access: true,
            shared_blases: true,
        }
    }
}

/// The default of [`ContextOptions::gpu_timeout`]: generous, since one trace of a large image
/// on lavapipe takes seconds, and short enough that a looping stage ends the command soon.
pub const DEFAULT_GPU_TIMEOUT: Duration = Duration::from_secs(120);

/// How ray tracing pipelines are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum PipelineKind {
    /// Each pipeline compiled whole from its stages.
    Monolithic,
    /// Each stage (or hit group) compiled once into a pipeline library, pipelines linked from
    /// them (VK_KHR_pipeline_library).
    Libraries,
}

/// The Vulkan instance, device, queue, extension loaders and allocator; everything else holds an `Arc` to it.
pub struct Context {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    pub physical: vk::PhysicalDevice,
    pub device: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    pub accel: khr::acceleration_structure::Device,
    pub rt: khr::ray_tracing_pipeline::Device,
    pub deferred: khr::deferred_host_operations::Device,
    pub info: DeviceInfo,
    allocator: ManuallyDrop<Mutex<Allocator>>,
    messenger: Option<Messenger>,
    // Boxed so the messenger's user-data pointer stays put; dropped after the messenger.
    validation_log: Box<ValidationLog>,
    /// Set once `close` has destroyed the device, so that `Drop` does not again.
    device_destroyed: bool,
    /// The pipeline cache every pipeline is created with, when one was asked for.
    pipeline_cache: Option<PipelineCache>,
    pipelines: PipelineKind,
    pipeline_threads: usize,
    gpu_timeout: Duration,
    shared_blases: AtomicBool,
    /// Set when GPU work did not finish: the device may still be running it, so nothing made
    /// from it may be destroyed (each owner's `Drop` leaks instead).
    abandoned: AtomicBool,
    /// Pipelines kept until the device goes (see [`Context::keeps_libraries`]).
    pub kept: KeptPipelines,
}

impl Context {
    /// Opens the first capable device (or the one `options` names), with validation as asked.
    pub fn new(options: &ContextOptions) -> Result<Arc<Self>> {
        // SAFETY: loading the system Vulkan loader; its entry points are used as documented.
        let entry = unsafe { ash::Entry::load() }?;
        let validation_log = Box::<ValidationLog>::default();
        let validate = options.validation != Validation::Off;
        if validate && !layer_available(&entry)? {
            return Err(Error::Unsupported(
                "validation was requested but VK_LAYER_KHRONOS_validation is not installed \
                 (Debian: apt-get install vulkan-validationlayers; or run cargo xtask setup)"
                    .into(),
            ));
        }
        let api = instance_api(&entry);
        let instance = create_instance(&entry, api, options.validation, &validation_log)?;
        let messenger = if validate {
            let loader = debug_utils::Instance::new(&entry, &instance);
            let info = validation::messenger_info(&validation_log);
            // SAFETY: validation_log is boxed and outlives the messenger (see Drop).
            let raw =
                unsafe { loader.create_debug_utils_messenger(&info, None) }.call("vkCreateDebugUtilsMessengerEXT")?;
            Some(Messenger { loader, raw })
        } else {
            None
        };
        let created = device_select::pick(&instance, options.device_filter.as_deref()).and_then(|candidate| {
            let optional = device_select::optional_extensions(&instance, candidate.physical)?;
            let robust = match options.robust_access {
                true => robustness(&instance, candidate.physical, &optional),
                false => Robustness::default(),
            };
            Ok((create_device(&instance, &candidate, &optional, robust)?, candidate, (optional, robust)))
        });
        let (device, candidate, (optional, robust)) = match created {
            Ok(made) => made,
            Err(e) => {
                destroy_instance(&instance, messenger);
                return Err(e);
            }
        };
        let mut info = device_info(&instance, candidate.physical, candidate.queue_family, candidate.name);
        info.pipeline_library = optional.contains(&ash::khr::pipeline_library::NAME);
        info.ray_query = optional.contains(&ash::khr::ray_query::NAME);
        info.robustness = robust;
        info.vulkan = info.vulkan.min((vk::api_version_major(api), vk::api_version_minor(api)));
        let pipelines = match options.pipelines {
            Some(PipelineKind::Libraries) if !info.pipeline_library => {
                // SAFETY: nothing was made from the device yet.
                unsafe { device.destroy_device(None) };
                destroy_instance(&instance, messenger);
                return Err(Error::Unsupported(format!(
                    "pipeline libraries were asked for, but {} lacks VK_KHR_pipeline_library (use --pipeline monolithic)",
                    info.name
                )));
            }
            Some(kind) => kind,
            None if info.pipeline_library => PipelineKind::Libraries,
            None => PipelineKind::Monolithic,
        };
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: candidate.physical,
            debug_settings: Default::default(),
            buffer_device_address: true,
            allocation_sizes: Default::default(),
        })
        .map_err(|source| Error::Allocation { what: "the allocator".into(), source })?;
        // SAFETY: the queue family was created with one queue.
        let queue = unsafe { device.get_device_queue(candidate.queue_family, 0) };
        // SAFETY: the physical device is live.
        let props = unsafe { instance.get_physical_device_properties(candidate.physical) };
        let pipeline_cache = options
            .pipeline_cache
            .as_ref()
            .map(|dir| PipelineCache::open(&device, &props, cache_file(dir, &props)))
            .transpose()?;
        Ok(Arc::new(Context {
            accel: khr::acceleration_structure::Device::new(&instance, &device),
            rt: khr::ray_tracing_pipeline::Device::new(&instance, &device),
            deferred: khr::deferred_host_operations::Device::new(&instance, &device),
            entry,
            instance,
            physical: candidate.physical,
            device,
            queue,
            queue_family: candidate.queue_family,
            info,
            allocator: ManuallyDrop::new(Mutex::new(allocator)),
            messenger,
            validation_log,
            device_destroyed: false,
            pipeline_cache,
            pipelines,
            pipeline_threads: options
                .pipeline_threads
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
                .max(1),
            gpu_timeout: options.gpu_timeout,
            shared_blases: AtomicBool::new(options.shared_blases),
            kept: KeptPipelines::default(),
            abandoned: AtomicBool::new(false),
        }))
    }

    /// The allocator; poisoning is ignored because the allocator holds no invariant a panic breaks.
    pub fn allocator(&self) -> std::sync::MutexGuard<'_, Allocator> {
        self.allocator.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Device memory for a resource with these requirements; `what` names it in errors.
    pub fn allocate(
        &self,
        what: &str,
        requirements: vk::MemoryRequirements,
        location: MemoryLocation,
        linear: bool,
    ) -> Result<Allocation> {
        let desc = AllocationCreateDesc {
            name: what,
            requirements,
            location,
            linear,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        };
        self.allocator().allocate(&desc).map_err(|source| Error::Allocation { what: what.into(), source })
    }

    /// Returns memory from [`Context::allocate`]; failures are logged, as they happen in Drop.
    pub fn free(&self, allocation: Allocation) {
        if let Err(e) = self.allocator().free(allocation) {
            log::error!("freeing device memory: {e}");
        }
    }

    /// Threads that join each pipeline creation; 0 when pipelines are not created as
    /// deferred operations: under the validation layer, whose version 1.3.239 (Debian
    /// bookworm) crashes in vkCreateRayTracingPipelinesKHR given one (measured on lavapipe,
    /// whole and linked pipelines; fixed upstream in 2024, Vulkan-ValidationLayers #8364).
    pub fn pipeline_threads(&self) -> usize {
        if self.messenger.is_some() {
            0
        } else {
            self.pipeline_threads
        }
    }

    /// How long one unit of GPU work or one pipeline creation may take.
    pub fn gpu_timeout(&self) -> Duration {
        self.gpu_timeout
    }

    /// Gives the device up: its work did not finish, or it was lost. From now on every object
    /// made from it is leaked rather than destroyed while the GPU may still use it.
    pub fn abandon(&self) {
        self.abandoned.store(true, Ordering::SeqCst);
    }

    /// Whether [`Context::abandon`] was called: `Drop`s leak their objects.
    pub fn abandoned(&self) -> bool {
        self.abandoned.load(Ordering::SeqCst)
    }

    /// Most geometries one bottom-level structure of this context holds: the device's
    /// `maxGeometryCount`, or 1 where [`ContextOptions::shared_blases`] is off.
    pub fn geometries_per_blas(&self) -> u64 {
        if self.shared_blases.load(Ordering::Relaxed) {
            self.info.max_geometry_count
        } else {
            1
        }
    }

    /// Turns [`ContextOptions::shared_blases`] on or off for the scenes uploaded from now on:
    /// a comparison of the two renders both on one context's pipelines.
    pub fn share_blases(&self, on: bool) {
        self.shared_blases.store(on, Ordering::Relaxed);
    }

    /// How this context makes ray tracing pipelines.
    pub fn pipeline_kind(&self) -> PipelineKind {
        self.pipelines
    }

    /// Whether every pipeline linked on this context shares the libraries made before it
    /// (`Context::kept`): on a CPU device. Lavapipe compiles a linked pipeline's code at its
    /// first trace, looked up in Mesa's shader cache by the pipeline's whole code, which holds
    /// each group's handle as a constant; handles are the device's running count, so libraries
    /// made afresh give the same stages new handles, and every pipeline after the first of a
    /// context compiled again (a test rendering one scene at nine scales compiled it nine
    /// times). A CPU device places no code for a timing to vary (each pipeline's code is
    /// loaded anew either way); a GPU's pipelines keep their own libraries, as the bench's
    /// placements assume.
    pub fn keeps_libraries(&self) -> bool {
        self.info.cpu_threads.is_some()
    }

    /// The pipeline cache to create pipelines with (null when none was asked for).
    pub fn pipeline_cache(&self) -> vk::PipelineCache {
        self.pipeline_cache.as_ref().map_or(vk::PipelineCache::null(), |c| c.raw)
    }

    /// The pipeline cache's file and the bytes of driver data it started from (0: cold);
    /// `None` when no cache was asked for.
    pub fn pipeline_cache_state(&self) -> Option<(&std::path::Path, usize)> {
        self.pipeline_cache.as_ref().map(|c| (c.file.as_path(), c.loaded_bytes))
    }

    /// Fails if the validation layer reported errors since the last check.
    pub fn check_validation(&self) -> Result<()> {
        let errors = self.validation_log.take_errors();
        match errors.first() {
            None => Ok(()),
            Some(first) => Err(Error::Validation { count: errors.len(), first: first.clone() }),
        }
    }
}

impl Context {
    /// Destroys the device and reports what the validation layer said about it, leaks above
    /// all: an object still alive when its device goes is a validation error
    /// (VUID-vkDestroyDevice-device-05137), which only teardown can reveal. Needs the last
    /// reference to the context.
    pub fn close(self: Arc<Self>) -> Result<()> {
        let mut ctx = Arc::try_unwrap(self).map_err(|ctx| {
            Error::Input(format!("closing a context still held in {} places", Arc::strong_count(&ctx)))
        })?;
        ctx.destroy_device();
        ctx.check_validation()
    }

    fn destroy_device(&mut self) {
        if std::mem::replace(&mut self.device_destroyed, true) {
            return;
        }
        // SAFETY: every object made from the device holds an Arc<Context>, so none is alive now;
        // the allocator goes before the device.
        unsafe {
            let _ = self.device.device_wait_idle();
            self.kept.destroy(&self.device);
            if let Some(cache) = self.pipeline_cache.take() {
                // A cache that cannot be written costs the next run its warm start, nothing more.
                if let Err(e) = cache.save(&self.device) {
                    log::warn!("saving the pipeline cache: {e}");
                }
                cache.destroy(&self.device);
            }
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_device(None);
        }
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        if self.abandoned() {
            // The device may still be running the work that never finished: waiting for it
            // would hang, destroying under it would crash. The process ends soon after.
            return;
        }
        self.destroy_device();
        // Nobody can be told any more: what the layer said at teardown goes to the log.
        if let Err(e) = self.check_validation() {
            log::error!("at Vulkan teardown: {e}");
        }
        // The messenger goes before the instance.
        destroy_instance(&self.instance, self.messenger.take());
    }
}

fn destroy_instance(instance: &ash::Instance, messenger: Option<Messenger>) {
    // SAFETY: nothing made from the instance is alive any more.
    unsafe {
        if let Some(m) = messenger {
            m.loader.destroy_debug_utils_messenger(m.raw, None);
        }
        instance.destroy_instance(None);
    }
}

fn layer_available(entry: &ash::Entry) -> Result<bool> {
    // SAFETY: plain enumeration.
    let layers = unsafe { entry.enumerate_instance_layer_properties() }.call("vkEnumerateInstanceLayerProperties")?;
    Ok(layers.iter().any(|l| l.layer_name_as_c_str() == Ok(validation::LAYER_NAME)))
}

/// Vulkan 1.3 where the loader has it (modules of SPIR-V 1.6 need it), else 1.2, what
/// twinray needs.
fn instance_api(entry: &ash::Entry) -> u32 {
    // SAFETY: a plain query of the loader.
    match unsafe { entry.try_enumerate_instance_version() } {
        Ok(Some(version)) if version >= vk::API_VERSION_1_3 => vk::API_VERSION_1_3,
        _ => vk::API_VERSION_1_2,
    }
}

fn create_instance(entry: &ash::Entry, api: u32, validation: Validation, log: &ValidationLog) -> Result<ash::Instance> {
    let validate = validation != Validation::Off;
    let app = vk::ApplicationInfo::default().application_name(c"twinray").engine_name(c"twinray").api_version(api);
    let layers = [validation::LAYER_NAME.as_ptr()];
    let extensions = [debug_utils::NAME.as_ptr()];
    let mut messenger_info = validation::messenger_info(log);
    let mut info = vk::InstanceCreateInfo::default().application_info(&app);
    let gpu = [
        vk::ValidationFeatureEnableEXT::GPU_ASSISTED,
        vk::ValidationFeatureEnableEXT::GPU_ASSISTED_RESERVE_BINDING_SLOT,
    ];
    let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&gpu);
    if validate {
        // The chained messenger also reports errors of vkCreateInstance/vkDestroyInstance.
        info = info.enabled_layer_names(&layers).enabled_extension_names(&extensions).push_next(&mut messenger_info);
    }
    if validation == Validation::GpuAssisted {
        info = info.push_next(&mut features);
    }
    // SAFETY: all pointers in `info` live until the call returns.
    unsafe { entry.create_instance(&info, None) }.call("vkCreateInstance")
}
