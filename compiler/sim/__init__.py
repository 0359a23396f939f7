"""rfc.sim: the harnesses of ``rfc sim`` that replay a bag through simulated logic.

The runtime's loop against the whole logic in GHDL or Verilator under cocotb
(`rfc.sim.hardware` prepares the job, `rfc.sim.cosim` runs in the simulator), in Verilator
with the DMA streams driven in C++ (`rfc.sim.stream_engine`), against a MyHDL model
(`rfc.sim.myhdl_sim`), and HLS accelerators C-simulated on the processor
(`rfc.sim.hls_csim`); the busy bits they all read (`rfc.sim.busy`).

The replay settings (`rfc.sim.settings.ReplaySettings`: drain and stall windows, seed,
progress, warnings) mean the same to every harness; ``rfc sim`` chooses them once.

Layer: above the driver, beside the wizard; it may import the driver and every layer under it
(it compiles the spec, lowers the plan and runs the toolchain), never the command line. The
runtime it drives knows nothing of it.
"""
