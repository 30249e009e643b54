"""What the workbench draws in the 3D view with Coin: the contact overlay, the
partitions, joint glyphs, simulation-model meshes, legends and colours."""
