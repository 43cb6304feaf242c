//! The bare minimum: a level from the asset folder, a 2D camera that draws the terrain,
//! and a click that carves a crater where the cursor is.
//!
//! `cargo run --release --example minimal`

use bevy::prelude::*;
use craterfield_bevy::prelude::*;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, CraterfieldPlugin))
        .add_systems(Startup, setup)
        .add_systems(Update, (fit_camera, carve_on_click))
        .run();
}

fn setup(mut commands: Commands, assets: Res<AssetServer>) {
    commands.spawn((Camera2d, TerrainView::default()));
    commands.insert_resource(StartMatch {
        level: assets.load("levels/default.ron"),
        settings: Settings::default(),
        players: 1,
        record: false,
    });
}

/// Shows the whole level: centred, as wide as the window.
fn fit_camera(
    cf: Option<Res<Craterfield>>,
    window: Single<&Window>,
    camera: Single<(&mut Transform, &mut Projection), With<Camera2d>>,
) {
    let Some(cf) = cf else { return };
    let (mut transform, mut projection) = camera.into_inner();
    let b = cf.level().bounds();
    transform.translation = ((b.min + b.max) * 0.5).extend(0.0);
    if let Projection::Orthographic(ortho) = projection.as_mut() {
        ortho.scale = (b.max.x - b.min.x) / window.width();
    }
}

fn carve_on_click(
    buttons: Res<ButtonInput<MouseButton>>,
    camera: Single<(&Camera, &GlobalTransform)>,
    window: Single<&Window>,
    mut edits: MessageWriter<TerrainEdit>,
) {
    let (camera, at) = camera.into_inner();
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    let Ok(world) = camera.viewport_to_world_2d(at, cursor) else {
        return;
    };
    if buttons.just_pressed(MouseButton::Left)
        && let Ok(crater) = TerrainEvent::carve(world, 40.0)
    {
        edits.write(TerrainEdit(crater));
    }
}
