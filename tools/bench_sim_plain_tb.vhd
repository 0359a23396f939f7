-- The plain testbench of a system's logic in GHDL: DMA transfers from a text file, no Python.
--
-- The simulator's own speed on the same stimulus as `rfc sim` (tools/bench_sim.py). The entity
-- `RFC_TOP` is replaced by the system's top level before analysis. The stimulus file holds the
-- idle pattern (one character per cycle, '1' idles the PS->PL stream; the PL->PS sink reads it
-- backwards), the cycle at which the run ends, then one PS->PL transfer per line: the cycle
-- (after reset) from which it may start, its length in bytes and its bytes in hex. Every PL->PS
-- transfer is written to the results file as one line of hex (the bytes whose tkeep is set).
-- A top level with a `busy` port (one bit per watched block; the line `-- RFC_BUSY` is replaced
-- by its association and `busy_bits` set) runs on past the end while any bit is high, for at
-- most `busy_cap` cycles, as `rfc sim` waits for it.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

entity rfc_plain_tb is
  generic (
    stimulus : string;
    results : string;
    lanes : positive := 8;
    busy_bits : positive := 1;
    busy_cap : natural := 100000
  );
end entity rfc_plain_tb;

architecture plain of rfc_plain_tb is
  signal aclk : std_logic := '0';
  signal aresetn : std_logic := '0';
  signal running : boolean := true;
  -- The DMA streams' signals, declared as every AXI-Stream testbench of rfc declares them.
  signal s_tdata : std_logic_vector(8 * lanes - 1 downto 0) := (others => '0');
  signal s_tkeep : std_logic_vector(lanes - 1 downto 0) := (others => '0');
  signal s_tvalid, s_tready, s_tlast : std_logic := '0';
  signal m_tdata : std_logic_vector(8 * lanes - 1 downto 0);
  signal m_tkeep : std_logic_vector(lanes - 1 downto 0);
  signal m_tvalid, m_tlast : std_logic;
  signal m_tready : std_logic := '0';
  signal busy : std_logic_vector(busy_bits - 1 downto 0) := (others => '0');

  function nibble(c : character) return natural is
  begin
    if c >= '0' and c <= '9' then
      return character'pos(c) - character'pos('0');
    elsif c >= 'a' and c <= 'f' then
      return character'pos(c) - character'pos('a') + 10;
    end if;
    return character'pos(c) - character'pos('A') + 10;
  end function;
begin
  dut : entity work.RFC_TOP
    port map (
      -- RFC_BUSY
      aclk => aclk,
      aresetn => aresetn,
      s_axis_mm2s_tdata => s_tdata,
      s_axis_mm2s_tkeep => s_tkeep,
      s_axis_mm2s_tvalid => s_tvalid,
      s_axis_mm2s_tready => s_tready,
      s_axis_mm2s_tlast => s_tlast,
      m_axis_s2mm_tdata => m_tdata,
      m_axis_s2mm_tkeep => m_tkeep,
      m_axis_s2mm_tvalid => m_tvalid,
      m_axis_s2mm_tready => m_tready,
      m_axis_s2mm_tlast => m_tlast
    );

  aclk <= not aclk after 5 ns when running;

  drive : process
    file source : text open read_mode is stimulus;
    variable pattern, frame : line;
    variable ending, due, left : natural := 0;
    variable loaded, have_next, sent : boolean := false;
    variable c1, c2 : character;
    variable data : std_logic_vector(8 * lanes - 1 downto 0);
    variable keep : std_logic_vector(lanes - 1 downto 0);
    variable at : natural;
  begin
    readline(source, pattern);
    readline(source, frame);
    read(frame, ending);
    for i in 1 to 6 loop  -- four cycles in reset, two out of it, then the drivers
      wait until rising_edge(aclk);
      if i = 4 then
        aresetn <= '1';
      end if;
    end loop;
    have_next := not endfile(source);
    if have_next then
      readline(source, frame);
      read(frame, due);
    end if;
    for now_cycle in 0 to ending + busy_cap - 1 loop
      exit when now_cycle >= ending and busy = (busy'range => '0');
      wait until rising_edge(aclk);
      at := now_cycle mod pattern'length;
      sent := s_tvalid = '1' and s_tready = '1';
      m_tready <= '0' when pattern(pattern'length - at) = '1' else '1';
      if s_tvalid = '0' or sent then
        if not loaded and have_next and now_cycle >= due then
          read(frame, left);
          read(frame, c1);  -- the space before the bytes
          loaded := true;
        end if;
        if loaded and pattern(at + 1) = '0' then
          data := (others => '0');
          keep := (others => '0');
          for lane in 0 to lanes - 1 loop
            exit when left = 0;
            read(frame, c1);
            read(frame, c2);
            data(8 * lane + 7 downto 8 * lane) :=
              std_logic_vector(to_unsigned(16 * nibble(c1) + nibble(c2), 8));
            keep(lane) := '1';
            left := left - 1;
          end loop;
          s_tdata <= data;
          s_tkeep <= keep;
          s_tvalid <= '1';
          s_tlast <= '1' when left = 0 else '0';
          if left = 0 then
            loaded := false;
            deallocate(frame);
            have_next := not endfile(source);
            if have_next then
              readline(source, frame);
              read(frame, due);
            end if;
          end if;
        else
          s_tvalid <= '0';
          s_tlast <= '0';
        end if;
      end if;
    end loop;
    running <= false;
    wait;
  end process;

  collect : process
    file sink : text open write_mode is results;
    variable received : line;
  begin
    wait until rising_edge(aclk);
    if m_tvalid = '1' and m_tready = '1' then
      for lane in 0 to lanes - 1 loop
        if m_tkeep(lane) = '1' then
          hwrite(received, m_tdata(8 * lane + 7 downto 8 * lane));
        end if;
      end loop;
      if m_tlast = '1' then
        writeline(sink, received);
      end if;
    end if;
  end process;
end architecture plain;
