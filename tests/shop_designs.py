"""Designs from the woodworkers' trials that more than one test module checks, as design
file texts (millimetres, the material's defaults but its thickness).

SIDE_TABLE_RACK  a 500 x 500 top, 18 mm, on four 45 mm legs nailed by their ends (no
                 apron), 25 kg on the top; case 'bump' adds an 80 N push at its edge,
                 which racks it.  In the elastic model the top sags 0.805 mm over its
                 482 mm span, 1.2075 mm with creep against 1.205 mm allowed.
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
