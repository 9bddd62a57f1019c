//! `[transient]` in the Rapier scenes (issue 16; moved from `tests/scenario/bad_input.rs`, whose
//! `set_transient_in_the_rapier_scenes` checks the refusals through `settle run`): the added mass
//! is accepted, with its default coefficient 0.5.

use std::path::Path;

#[test]
fn the_added_mass_is_accepted_in_the_rapier_scenes() {
    for file in ["restitution_drop.toml", "paste_68_balls.toml"] {
        let on = ["transient.added_mass=true".to_string()];
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios")
            .join(file);
        let p = crate::scenario::parse(&path, &on).expect("added mass accepted");
        assert_eq!(p.common.added_mass_coefficient(), 0.5);
    }
}
