"""FE validation: read an FE model's output where it lives (formats), in its frame (frames) and units
(units), judge it with the statistics validators use (stats), over a mesh sequence (validate), and
report it (report, command); export the reference for ParaView (vtu)."""
