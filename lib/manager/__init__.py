"""The manager: the DMA side of a generated system (docs/protocol.md).

PS→PL, `chunk_demux` reads each chunk's header and routes its payload to the subscriber
converter named by the id. PL→PS, `chunk_mux` lets the scheduler pick a publisher and writes a
chunk header in front of its payload, ending the chunk early when a preemptive scheduler moves
the grant away.
"""
