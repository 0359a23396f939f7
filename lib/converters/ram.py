"""A simple dual-port RAM: one write port, one registered read port (read-first).

The FIFOs that hold a message's strings and sequences can be large (a whole image). In VHDL the
memory is a variable of one clocked process — the template block-RAM inference expects, and
cheap for GHDL, which would otherwise create a signal per bit of every word; Verilog gets the
usual ``reg`` array. MyHDL's simulator runs the Python body, which keeps only the words written
(no signal per word: elaborating millions of them would take minutes).
"""

from __future__ import annotations

from myhdl import always, block

from rfc.lib.types import Instances, SignalLike


@block
def ram(
    clk: SignalLike,
    w_enable: SignalLike,
    w_address: SignalLike,
    w_data: SignalLike,
    r_enable: SignalLike,
    r_address: SignalLike,
    r_data: SignalLike,
    depth: int,
) -> Instances:
    """`depth` words of `len(w_data)` bits; `r_data` shows word `r_address` after `r_enable`.

    A read of the address written in the same cycle returns the old word (read-first). The
    memory has no initial contents (a FIFO reads only words it wrote), so synthesis gets a
    plain block RAM with nothing to initialize.
    """
    words: dict[int, int] = {}
    width = len(w_data)  # noqa: F841 (the Verilog template reads it)

    @always(clk.posedge)
    def access() -> None:
        if r_enable:
            r_data.next = words.get(int(r_address), 0)
        if w_enable:
            words[int(w_address)] = int(w_data)

    r_data.driven = "reg"
    for port in (clk, w_enable, w_address, w_data, r_enable, r_address):
        port.read = True
    return access


ram.vhdl_code = """
${r_data}_memory: process ($clk) is
    type words_t is array (0 to $depth - 1) of unsigned($r_data'range);
    variable words: words_t;  -- no initial contents: a word is read only once written
begin
    if rising_edge($clk) then
        if $r_enable = '1' then
            $r_data <= words(to_integer($r_address));
        end if;
        if $w_enable = '1' then
            words(to_integer($w_address)) := $w_data;
        end if;
    end if;
end process ${r_data}_memory;
"""

ram.verilog_code = """
reg [$width - 1:0] ${r_data}_words [0:$depth - 1];
always @(posedge $clk) begin
    if ($r_enable) $r_data <= ${r_data}_words[$r_address];
    if ($w_enable) ${r_data}_words[$w_address] <= $w_data;
end
"""
