//! GPU time of recorded work from timestamp queries (when the device has
//! `TIMESTAMP_QUERY`), for benchmarks. Reading results waits for the GPU.

use super::GpuError;
#[cfg(not(target_family = "wasm"))]
use super::map_read;
use super::map_read_async;

/// A set of timestamp pairs and the buffers to resolve and read them.
pub struct Timestamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    pairs: u32,
    period_ns: f64,
}

impl Timestamps {
    /// Room for `pairs` begin/end pairs; `None` when the device lacks timestamp queries.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, pairs: u32) -> Option<Timestamps> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) || pairs == 0 {
            return None;
        }
        let count = pairs * 2;
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("craterfield timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let bytes = u64::from(count) * 8;
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("craterfield timestamp resolve"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("craterfield timestamp read"),
            size: bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Some(Timestamps {
            set,
            resolve,
            read,
            pairs,
            period_ns: f64::from(queue.get_timestamp_period()),
        })
    }

    /// The query set and the first index of pair `i`.
    pub fn pair(&self, i: u32) -> Option<(&wgpu::QuerySet, u32)> {
        (i < self.pairs).then_some((&self.set, i * 2))
    }

    /// Records the resolve and copy; submit before [`Self::read_ms`].
    pub fn encode_resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..self.pairs * 2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, self.resolve.size());
    }

    /// Every timestamp's time in milliseconds after the first one, after the resolve was
    /// submitted (for passes timed back to back, where the gaps matter too). Native
    /// targets only (see [`Self::read_marks_ms_async`]).
    #[cfg(not(target_family = "wasm"))]
    pub fn read_marks_ms(&self, device: &wgpu::Device) -> Result<Vec<f64>, GpuError> {
        map_read(device, &self.read, |data| self.marks_ms(data))
    }

    /// Milliseconds of every pair, after the resolve was submitted. Native targets only
    /// (see [`Self::read_ms_async`]).
    #[cfg(not(target_family = "wasm"))]
    pub fn read_ms(&self, device: &wgpu::Device) -> Result<Vec<f64>, GpuError> {
        map_read(device, &self.read, |data| self.pairs_ms(data))
    }

    /// [`Self::read_marks_ms`] for every target, awaiting the mapping.
    pub async fn read_marks_ms_async(&self, device: &wgpu::Device) -> Result<Vec<f64>, GpuError> {
        map_read_async(device, &self.read, |data| self.marks_ms(data)).await
    }

    /// [`Self::read_ms`] for every target, awaiting the mapping.
    pub async fn read_ms_async(&self, device: &wgpu::Device) -> Result<Vec<f64>, GpuError> {
        map_read_async(device, &self.read, |data| self.pairs_ms(data)).await
    }

    fn marks_ms(&self, data: &[u8]) -> Vec<f64> {
        let ticks: &[u64] = bytemuck::cast_slice(data);
        let first = ticks.first().copied().unwrap_or(0);
        ticks
            .iter()
            .map(|t| t.wrapping_sub(first) as f64 * self.period_ns / 1.0e6)
            .collect()
    }

    fn pairs_ms(&self, data: &[u8]) -> Vec<f64> {
        let ticks: &[u64] = bytemuck::cast_slice(data);
        ticks
            .chunks(2)
            .map(|p| p[1].wrapping_sub(p[0]) as f64 * self.period_ns / 1.0e6)
            .collect()
    }
}
