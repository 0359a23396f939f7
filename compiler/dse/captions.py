"""The captions of the sweep's figures, apart from matplotlib: the report names them too."""

#: What each figure shows (file name → caption).
CAPTIONS = {
    "figure6": "Figure 6: schedulers' resource utilization (LUT, FF) versus N",
    "figure7": "Figure 7: preemptions per accelerator (per completed transaction)",
    "figure8": "Figure 8: accelerators that completed at least one transaction (full) or "
    "only got the grant (hatched)",
    "figure9": "Figure 9: communication channel utilization",
    "figure10": "Figure 10: (a) average response time, (b) average lateness",
    "figure11": "Figure 11: corner cases, preemptions per accelerator",
    "figure12": "Figure 12: corner cases, average response time",
    "figure13": "Figure 13: corner cases, average lateness",
    "figure14": "Figure 14: combined schedulers, accelerators granted and completed",
    "table3": "Table 3: resource-latency EDF trade-off (ROEDF / LOEDF)",
}
