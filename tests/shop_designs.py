"""Designs from the woodworkers' trials that more than one test module checks, as design
file texts (millimetres, the material's defaults but its thickness).

SIDE_TABLE_RACK  a 500 x 500 top, 18 mm, on four 45 mm legs nailed by their ends (no
                 apron), 25 kg on the top; case 'bump' adds an 80 N push at its edge,
                 which racks it.  In the elastic model the top sags 0.805 mm over its
                 482 mm span, 1.2075 mm with creep against 1.205 mm allowed.
WALL_SHELF       a 600 x 250 shelf, 18 mm, nailed by its back edge (4 nails listed) to
                 a back board screwed to the wall (two 400 N fixings), 25 kg of books
                 spread on it: its nails pull out, and its one beam, held at the
                 joint's middle, reads a sag it does not have.
COAT_RACK        a 900 x 150 back board, 18 mm, flat on the wall, hung on two plugs
                 rated 120 N (the right one at z = {right}: 1620 as drawn, level with
                 the left), four 5 kg coats on it and a 900 x 250 hat shelf nailed onto
                 its top edge with 8 kg spread on it: in the rigid model the plugs hold
                 147.1 N each; in the elastic one the shelf's back corners bear on the
                 wall and it reads a span between them.
TILE_BENCH       a 1000 mm bench of 18 mm boards at 600 kg/m^3 on tiles (mu 0.15), 70 kg
                 on it, shoved with 150 N: it slides (mu W = 113 N); non-slip pads with
                 mu 0.2 hold it.
SPLAYED_STOOL    a 360 x 300 seat on four legs splayed 10 degrees, each nailed by one
                 nail, 90 kg on the seat (rigid model): the legs spread and all four
                 nails pull out.
WALL_SHELF_LONG  a 1200 x 250 shelf, 12 mm, on two 150 x 120 cleats 900 mm apart, each
                 screwed once to the wall 30 mm above its middle (196 N fixings), 25 kg
                 of books spread on it: each screw pulls about 181 N out of the wall,
                 past its rating with the weight it holds up, and the shelf sags.
"""

SIDE_TABLE_RACK = """\
furncheck: 1
name: side-table-rack
material: {thickness: 18}
planks:
  - {id: top, size: [500, 500], center: [0, 0, 591]}
  - {id: leg_pp, size: [582, 45], center: [241, 227.5, 291], rotation: [0, -90, 0]}
  - {id: leg_mp, size: [582, 45], center: [-241, 227.5, 291], rotation: [0, -90, 0]}
  - {id: leg_pm, size: [582, 45], center: [241, -227.5, 291], rotation: [0, -90, 0]}
  - {id: leg_mm, size: [582, 45], center: [-241, -227.5, 291], rotation: [0, -90, 0]}
loads:
  - {plank: top, mass: 25}
load_cases:
  bump:
    include: [default]
    loads:
      - {plank: top, force: [80, 0, 0], at: [-250, 0, 600]}
"""


WALL_SHELF = """\
furncheck: 1
name: wall-shelf-few-nails
material: {thickness: 18}
walls:
  - {point: [0, 0, 0], normal: [0, 1, 0]}
planks:
  - {id: back, size: [600, 200], center: [0, 9, 1400], rotation: [90, 0, 0]}
  - {id: shelf, size: [600, 250], center: [0, 143, 1400]}
joints:
  - {planks: [back, shelf], nails: 4}
anchors:
  - {plank: back, at: [-200, 0, 1470], wall: 0, capacity: 400}
  - {plank: back, at: [200, 0, 1470], wall: 0, capacity: 400}
loads:
  - {plank: shelf, mass: 25, spread: true}
"""

WALL_SHELF_ONE_BRACKET = """\
furncheck: 1
name: wall-shelf-one-bracket
material: {thickness: 18}
walls:
  - {point: [0, 0, 0], normal: [0, 1, 0]}
planks:
  - {id: back, size: [600, 200], center: [0, 9, 1400], rotation: [90, 0, 0]}
  - {id: shelf, size: [600, 250], center: [0, 143, 1400]}
  - {id: bracket, size: [250, 100], center: [-291, 143, 1341], rotation: [90, 0, 90]}
anchors:
  - {plank: back, at: [-200, 0, 1470], wall: 0, capacity: 400}
  - {plank: back, at: [200, 0, 1470], wall: 0, capacity: 400}
loads:
  - {plank: shelf, mass: 25, spread: true}
"""

WALL_SHELF_ON_RAIL = """\
furncheck: 1
name: wall-shelf-on-rail
material: {thickness: 18}
walls: [{point: [0, 0, 0], normal: [0, 1, 0]}]
planks:
  - {id: rail, size: [900, 100], center: [0, 9, 1400], rotation: [90, 0, 0]}
  - {id: shelf, size: [900, 250], center: [0, 125, 1459]}
anchors:
  - {plank: rail, at: [-300, 0, 1425], wall: 0, capacity: 400}
  - {plank: rail, at: [300, 0, 1425], wall: 0, capacity: 400}
loads:
  - {plank: shelf, mass: 30, spread: true}
"""

THIN_SHELF_ON_RAIL = """\
furncheck: 1
name: wall-shelf-rail-12mm
material: {thickness: 12}
walls: [{point: [0, 0, 0], normal: [0, 1, 0]}]
planks:
  - {id: rail, size: [900, 100], center: [0, 9, 1450], rotation: [90, 0, 0], thickness: 18}
  - {id: shelf, size: [900, 300], center: [0, 150, 1506]}
anchors:
  - {plank: rail, at: [-350, 0, 1480], wall: 0, capacity: 700}
  - {plank: rail, at: [350, 0, 1480], wall: 0, capacity: 700}
loads:
  - {plank: shelf, mass: 40, spread: true}
"""

LIPPED_SHELF = """\
furncheck: 1
name: lipped-shelf
walls: [{point: [0, 0, 0], normal: [0, 1, 0]}]
planks:
  - {id: cleat, size: [800, 80], center: [0, 6, 1400], rotation: [90, 0, 0]}
  - {id: shelf, size: [800, 200], center: [0, 100, 1446]}
  - {id: lip, size: [800, 30], center: [0, 194, 1467], rotation: [90, 0, 0]}
anchors:
  - {plank: cleat, at: [-300, 0, 1420], wall: 0, capacity: 400}
  - {plank: cleat, at: [300, 0, 1420], wall: 0, capacity: 400}
loads:
  - {plank: shelf, mass: 8, spread: true}
"""

COAT_RACK = """\
furncheck: 1
name: coat-rack
material: {{thickness: 18}}
walls:
  - {{point: [0, 0, 0], normal: [0, 1, 0]}}
planks:
  - {{id: back, size: [900, 150], center: [0, 9, 1600], rotation: [90, 0, 0]}}
  - {{id: shelf, size: [900, 250], center: [0, 125, 1684]}}
anchors:
  - {{plank: back, at: [-350, 0, 1620], wall: 0, capacity: 120}}
  - {{plank: back, at: [350, 0, {right}], wall: 0, capacity: 120}}
loads:
  - {{plank: back, mass: 5, at: [-300, 18, 1560]}}
  - {{plank: back, mass: 5, at: [-100, 18, 1560]}}
  - {{plank: back, mass: 5, at: [100, 18, 1560]}}
  - {{plank: back, mass: 5, at: [300, 18, 1560]}}
  - {{plank: shelf, mass: 8, spread: true}}
"""

TILE_BENCH = """\
furncheck: 1
name: tile-bench
model: rigid
material: {thickness: 18, density: 600, friction: 0.15}
planks:
  - {id: seat, size: [1000, 300], center: [0, 0, 441]}
  - {id: end_l, size: [432, 300], center: [-441, 0, 216], rotation: [0, -90, 0]}
  - {id: end_r, size: [432, 300], center: [441, 0, 216], rotation: [0, -90, 0]}
  - {id: rail, size: [864, 80], center: [0, 0, 300], rotation: [90, 0, 0]}
loads:
  - {plank: seat, mass: 70, at: [-300, 0, 450]}
  - {plank: seat, force: [150, 0, 0], at: [-500, 0, 441]}
"""

SPLAYED_STOOL = """\
furncheck: 1
name: splayed-stool
model: rigid
material: {thickness: 18, density: 600, friction: 0.15}
planks:
  - {id: seat, size: [360, 300], center: [0, 0, 441.0094]}
  - {id: leg_pp, size: [435.5, 80], center: [178.9486, 100, 216.0047], rotation: [0, -100, 0]}
  - {id: leg_pm, size: [435.5, 80], center: [178.9486, -100, 216.0047], rotation: [0, -100, 0]}
  - {id: leg_mp, size: [435.5, 80], center: [-178.9486, 100, 216.0047], rotation: [0, -80, 0]}
  - {id: leg_mm, size: [435.5, 80], center: [-178.9486, -100, 216.0047], rotation: [0, -80, 0]}
joints:
  - {planks: [seat, leg_pp], nails: 1}
  - {planks: [seat, leg_pm], nails: 1}
  - {planks: [seat, leg_mp], nails: 1}
  - {planks: [seat, leg_mm], nails: 1}
loads:
  - {plank: seat, mass: 90, at: [0, 0, 450.0094]}
"""

WALL_SHELF_LONG = """\
furncheck: 1
name: wall-shelf-long
units: mm
walls:
  - {point: [0, 0, 0], normal: [0, 1, 0]}
planks:
  - {id: cleat_l, size: [150, 120], center: [-450, 6, 1400], rotation: [90, 0, 0]}
  - {id: cleat_r, size: [150, 120], center: [450, 6, 1400], rotation: [90, 0, 0]}
  - {id: shelf, size: [1200, 250], center: [0, 125, 1466]}
anchors:
  - {plank: cleat_l, at: [-450, 0, 1430], wall: 0, capacity: 196}
  - {plank: cleat_r, at: [450, 0, 1430], wall: 0, capacity: 196}
loads:
  - {plank: shelf, mass: 25, spread: true}
"""
