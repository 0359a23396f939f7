"""Whole-system hardware: the holistic model becomes the programmable logic's VHDL.

The flow: `components` generates every entity the logic instantiates (converters, manager,
accelerators with their wrappers, handshake forks), `top` wires them into one structural
netlist from the model's hardware connections, and `system.generate_system` returns the lot —
VHDL in compile order, the netlist, and what the Vivado and HLS scripts need.
"""
