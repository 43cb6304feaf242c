//! The explosion grid mirrored in GPU buffers, uploaded incrementally: each frame only new
//! or changed events, cells whose revision changed, their event lists and their bricks are
//! written. Buffers grow by doubling (then everything is re-sent once); event lists live in
//! one arena where each cell keeps a slot with spare room, repacked when it runs out.

use wgpu::util::DeviceExt;

use super::uniforms::{GpuCell, GpuEvent, GridFrame, encode_state};
use super::{GpuError, RenderError};
use craterfield_field::Event;
use craterfield_field::Grid;
use craterfield_field::Sdf;
use craterfield_field::Terrain;

/// What one synchronisation wrote.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadStats {
    /// Events written.
    pub events: usize,
    /// Cell records written.
    pub cells: usize,
    /// Event-list entries written.
    pub list_entries: usize,
    /// Bricks written.
    pub bricks: usize,
    /// Bytes written in all.
    pub bytes: u64,
    /// Whether buffers were (re)allocated, so bind groups must be rebuilt.
    pub reallocated: bool,
}

/// Identity of a grid's geometry: a different one means a different terrain.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Geometry {
    dims: (u32, u32),
    origin: [u32; 2],
    cell_size: u32,
    resolution: u32,
}

impl Geometry {
    fn of(grid: &Grid) -> Geometry {
        Geometry {
            dims: grid.dims(),
            origin: [grid.origin().x.to_bits(), grid.origin().y.to_bits()],
            cell_size: grid.cell_size().to_bits(),
            resolution: grid.brick_resolution(),
        }
    }
}

/// A storage buffer with a capacity in elements.
struct Storage {
    buffer: wgpu::Buffer,
    capacity: u64,
}

impl Storage {
    fn new(device: &wgpu::Device, label: &str, elements: u64, element_bytes: u64) -> Storage {
        let capacity = elements.max(1);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: capacity * element_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Storage { buffer, capacity }
    }
}

/// The GPU copy of a terrain's grid.
pub(crate) struct GridMirror {
    geometry: Option<Geometry>,
    events: Storage,
    sent_events: Vec<Event>,
    cells: Storage,
    sent_revisions: Vec<u64>,
    lists: Storage,
    /// Per cell: first arena entry and room.
    slots: Vec<(u32, u32)>,
    arena_used: u32,
    /// Per brick id: its values (f32 bits) then its materials, `2 (n + 1)^2` words.
    bricks: Storage,
    max_binding: u64,
}

/// Arena room given to a list of `len` events: spare space so most growth stays in place.
fn room_for(len: u32) -> u32 {
    len.next_power_of_two().max(4)
}

/// Words (f32 values or u32 materials) of one brick at resolution `n`.
fn brick_words(n: u32) -> u64 {
    u64::from(n + 1) * u64::from(n + 1)
}

impl GridMirror {
    /// Empty buffers on `device`.
    pub(crate) fn new(device: &wgpu::Device) -> GridMirror {
        GridMirror {
            geometry: None,
            events: Storage::new(device, "craterfield events", 1, 32),
            sent_events: Vec::new(),
            cells: Storage::new(device, "craterfield cells", 1, 16),
            sent_revisions: Vec::new(),
            lists: Storage::new(device, "craterfield lists", 1, 4),
            slots: Vec::new(),
            arena_used: 0,
            bricks: Storage::new(device, "craterfield bricks", 1, 4),
            max_binding: {
                let limits = device.limits();
                limits
                    .max_storage_buffer_binding_size
                    .min(limits.max_buffer_size)
            },
        }
    }

    /// The buffers in binding order 1..=4 of `shaders/field.wgsl`.
    pub(crate) fn buffers(&self) -> [&wgpu::Buffer; 4] {
        [
            &self.events.buffer,
            &self.cells.buffer,
            &self.lists.buffer,
            &self.bricks.buffer,
        ]
    }

    /// The grid geometry part of the frame uniform.
    pub(crate) fn frame<F: Sdf>(terrain: &Terrain<F>) -> GridFrame {
        let grid = terrain.grid();
        let (nx, ny) = grid.dims();
        GridFrame {
            band: terrain.options().band,
            origin: grid.origin(),
            cell_size: grid.cell_size(),
            brick_spacing: grid.brick_spacing(),
            dims: [nx, ny],
            brick_res: grid.brick_resolution(),
            tick: terrain.tick(),
        }
    }

    /// Brings the buffers up to date with `terrain`.
    pub(crate) fn sync<F: Sdf>(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        terrain: &Terrain<F>,
    ) -> Result<UploadStats, RenderError> {
        let grid = terrain.grid();
        let mut stats = UploadStats::default();
        let geometry = Geometry::of(grid);
        if self.geometry != Some(geometry) {
            self.reset(device, grid)?;
            self.geometry = Some(geometry);
            stats.reallocated = true;
        }
        self.sync_events(device, queue, terrain.events(), &mut stats)?;
        self.sync_cells(device, queue, grid, &mut stats)?;
        Ok(stats)
    }

    fn check_size(&self, what: &'static str, bytes: u64) -> Result<(), RenderError> {
        if bytes > self.max_binding {
            return Err(GpuError::LimitsTooLow {
                what,
                needed: bytes,
                limit: self.max_binding,
            }
            .into());
        }
        Ok(())
    }

    /// Fresh buffers sized for `grid`, nothing sent yet.
    fn reset(&mut self, device: &wgpu::Device, grid: &Grid) -> Result<(), RenderError> {
        let cells = grid.cell_count() as u64;
        self.check_size("grid cells (bytes)", cells * 16)?;
        self.cells = Storage::new(device, "craterfield cells", cells, 16);
        self.sent_revisions = vec![u64::MAX; grid.cell_count()];
        self.slots = vec![(0, 0); grid.cell_count()];
        self.arena_used = 0;
        self.sent_events.clear();
        Ok(())
    }

    fn sync_events(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        events: &[Event],
        stats: &mut UploadStats,
    ) -> Result<(), RenderError> {
        let mut first = self
            .sent_events
            .iter()
            .zip(events)
            .take_while(|(a, b)| a == b)
            .count();
        if events.len() as u64 > self.events.capacity {
            let capacity = (events.len() as u64).next_power_of_two();
            self.check_size("events (bytes)", capacity * 32)?;
            self.events = Storage::new(device, "craterfield events", capacity, 32);
            stats.reallocated = true;
            first = 0;
        }
        if first < events.len() {
            let data: Vec<GpuEvent> = events[first..].iter().map(GpuEvent::from).collect();
            let bytes = bytemuck::cast_slice(&data);
            queue.write_buffer(&self.events.buffer, first as u64 * 32, bytes);
            stats.events += data.len();
            stats.bytes += bytes.len() as u64;
        }
        self.sent_events.truncate(first);
        self.sent_events.extend_from_slice(&events[first..]);
        Ok(())
    }

    fn sync_cells(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        grid: &Grid,
        stats: &mut UploadStats,
    ) -> Result<(), RenderError> {
        let dirty: Vec<usize> = grid.changed_since(&self.sent_revisions).collect();
        if dirty.is_empty() && !stats.reallocated {
            return Ok(());
        }
        let needs_room = dirty.iter().any(|&i| {
            let len = grid.cell(i).map_or(0, |c| c.events().len()) as u32;
            len > self.slots.get(i).map_or(0, |s| s.1)
        });
        let extra: u64 = dirty
            .iter()
            .map(|&i| {
                grid.cell(i)
                    .map_or(0, |c| room_for(c.events().len() as u32).into())
            })
            .sum();
        if needs_room && u64::from(self.arena_used) + extra > self.lists.capacity {
            self.repack(device, grid)?;
            stats.reallocated = true;
        }
        self.ensure_brick_room(device, grid, stats)?;
        let all: Vec<usize>;
        let targets: &[usize] = if stats.reallocated {
            all = (0..grid.cell_count()).collect();
            &all
        } else {
            &dirty
        };
        for &i in targets {
            self.send_cell(queue, grid, i, stats);
        }
        Ok(())
    }

    /// Lays every cell's slot out again with room to grow, in a buffer big enough for them.
    fn repack(&mut self, device: &wgpu::Device, grid: &Grid) -> Result<(), RenderError> {
        let mut next = 0u32;
        for (slot, cell) in self.slots.iter_mut().zip(grid.cells()) {
            let room = room_for(cell.events().len() as u32);
            *slot = (next, room);
            next = next.saturating_add(room);
        }
        self.arena_used = next;
        let capacity = (u64::from(next) * 2).max(1024);
        self.check_size("event lists (bytes)", capacity * 4)?;
        self.lists = Storage::new(device, "craterfield lists", capacity, 4);
        Ok(())
    }

    /// Grows the brick buffers to hold every brick id the grid references.
    fn ensure_brick_room(
        &mut self,
        device: &wgpu::Device,
        grid: &Grid,
        stats: &mut UploadStats,
    ) -> Result<(), RenderError> {
        let words = 2 * brick_words(grid.brick_resolution());
        let needed = grid
            .cells()
            .filter_map(|c| c.state().brick())
            .map(|id| u64::from(id) + 1)
            .max()
            .unwrap_or(0);
        if needed * words <= self.bricks.capacity {
            return Ok(());
        }
        let bricks = needed.next_power_of_two();
        self.check_size("bricks (bytes)", bricks * words * 4)?;
        self.bricks = Storage::new(device, "craterfield bricks", bricks * words, 4);
        stats.reallocated = true;
        Ok(())
    }

    /// Writes cell `i`'s record, list and brick.
    fn send_cell(&mut self, queue: &wgpu::Queue, grid: &Grid, i: usize, stats: &mut UploadStats) {
        let Some(cell) = grid.cell(i) else {
            return;
        };
        let len = cell.events().len() as u32;
        let Some(slot) = self.slots.get_mut(i) else {
            return;
        };
        if len > slot.1 {
            let room = room_for(len);
            *slot = (self.arena_used, room);
            self.arena_used += room;
        }
        let (start, _) = *slot;
        if u64::from(start) + u64::from(len) > self.lists.capacity {
            // Unreachable: `sync_cells` repacks before any slot could overflow.
            return;
        }
        if len > 0 {
            let bytes = bytemuck::cast_slice(cell.events());
            queue.write_buffer(&self.lists.buffer, u64::from(start) * 4, bytes);
            stats.list_entries += cell.events().len();
            stats.bytes += bytes.len() as u64;
        }
        let (state, payload) = encode_state(cell.state());
        let record = GpuCell {
            state,
            payload,
            start,
            len,
        };
        queue.write_buffer(
            &self.cells.buffer,
            i as u64 * 16,
            bytemuck::bytes_of(&record),
        );
        stats.cells += 1;
        stats.bytes += 16;
        if let Some(id) = cell.state().brick() {
            self.send_brick(queue, grid, id, stats);
        }
        if let Some(sent) = self.sent_revisions.get_mut(i) {
            *sent = cell.revision();
        }
    }

    fn send_brick(&self, queue: &wgpu::Queue, grid: &Grid, id: u32, stats: &mut UploadStats) {
        let Some((values, materials)) = grid.brick_samples(id) else {
            return;
        };
        let words = brick_words(grid.brick_resolution());
        let fits = (u64::from(id) + 1) * 2 * words <= self.bricks.capacity;
        if values.len() as u64 != words || !fits {
            return;
        }
        let data: Vec<u32> = values
            .iter()
            .map(|v| v.to_bits())
            .chain(materials.iter().map(|&m| u32::from(m)))
            .collect();
        let offset = u64::from(id) * 2 * words * 4;
        queue.write_buffer(&self.bricks.buffer, offset, bytemuck::cast_slice(&data));
        stats.bricks += 1;
        stats.bytes += words * 8;
    }
}

/// A buffer initialised from bytes (uniforms, palettes).
pub(crate) fn buffer_with(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage,
    })
}
