// examples/cattaneo_cylinders.geo coarsened for the tests: 2 mm elements only within 2.5 cm of the
// contact point (the contact half-width is about 2.1 cm), 0.5 m far from it.
fine = 0.002;
near = 0.025;
far = 0.5;
coarse = 0.5;
Include "../../examples/cattaneo_cylinders.geo";
