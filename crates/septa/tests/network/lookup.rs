//! The look-up tables (Du et al. Sec. 6) and the single-polygon templates
//! built on them give, grid-wide, the same network.json (apart from timings)
//! as the incremental construction in every tet: the fast paths change the
//! speed, never the output.

use crate::common;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::io::read_grid_input;
use septa::network::{compute, Network, NetworkOptions};

fn json(net: &Network, tag: &str) -> String {
    common::network_json(net, tag)
}

#[test]
fn tables_and_templates_give_the_incremental_network() {
    let dir = common::shared_data().join("isn");
    for name in ["ia4_R20", "mi4_R20", "ia18_R20", "mi18_R20", "nested8_R20", "shifted4_ia_eps1e-7_R2_s0"] {
        let mode = if name.contains("mi") { Mode::Mi } else { Mode::Ia };
        let input = read_grid_input(&dir.join(format!("{name}.npz"))).unwrap();
        let g = BoxGrid::new([input.grid_res.unwrap(); 3], input.bbox.unwrap(), Split::Five).unwrap();
        let grid = Grid::Box(g);
        let mut texts = Vec::new();
        for lookup in [true, false] {
            let mut o = NetworkOptions::new(mode);
            o.lookup = lookup;
            let net = compute(&grid, &input.values, input.k, &o).unwrap();
            assert!(!net.face_label.is_empty(), "{name}: empty network");
            texts.push(json(&net, if lookup { "t" } else { "i" }));
        }
        assert!(texts[0] == texts[1], "{name}: tables/templates and incremental differ");
    }
}
