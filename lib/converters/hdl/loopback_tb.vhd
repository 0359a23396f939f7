-- Testbench for rfc_loopback (rfc.lib.converters.loopback), driven by files.
--
-- INPUT_FILE holds one line per beat: "<tlast> <bytes> <tdata in hex, lane 0 last>", frames one
-- after another. Each frame is sent at full rate once the previous one has come out, so that
-- the cycle counts of one message do not include waiting for another. OUTPUT_FILE receives
--   "start <cycle>"   the first beat of a frame entered the subscriber,
--   "last <cycle>"    the frame's last beat entered the subscriber,
--   "fields <cycle>"  the subscriber presented the message's fields (msg_valid),
--   "beat <cycle> <tlast> <tkeep> <tdata>"  every beat the publisher sent (hex),
--   "end <cycle> <frame_length> <error_count>"  the publisher sent the frame's last beat,
-- and "stall <cycle>" if nothing moves for STALL_CYCLES cycles (the run then stops).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

entity rfc_loopback_tb is
    generic (
        WIDTH: positive := 8;
        INPUT_FILE: string := "frames.txt";
        OUTPUT_FILE: string := "events.txt";
        STALL_CYCLES: positive := 100000
    );
end entity rfc_loopback_tb;

architecture files of rfc_loopback_tb is
    signal clk: std_logic := '0';
    signal rst: std_logic := '1';
    signal s_tdata: std_logic_vector(8 * WIDTH - 1 downto 0) := (others => '0');
    signal s_tkeep: std_logic_vector(WIDTH - 1 downto 0) := (others => '0');
    signal s_tvalid, s_tready, s_tlast: std_logic := '0';
    signal m_tdata: std_logic_vector(8 * WIDTH - 1 downto 0);
    signal m_tkeep: std_logic_vector(WIDTH - 1 downto 0);
    signal m_tvalid, m_tlast: std_logic;
    signal frame_length, error_count: std_logic_vector(31 downto 0);
    signal fields_valid: std_logic;
    signal cycle: natural := 0;
    signal frame_out: natural := 0;
    signal finished, stalled: boolean := false;
begin
    dut: entity work.rfc_loopback
        port map (
            clk => clk, rst => rst,
            s_axis_tdata => s_tdata, s_axis_tkeep => s_tkeep, s_axis_tvalid => s_tvalid,
            s_axis_tready => s_tready, s_axis_tlast => s_tlast,
            m_axis_tdata => m_tdata, m_axis_tkeep => m_tkeep, m_axis_tvalid => m_tvalid,
            m_axis_tready => '1', m_axis_tlast => m_tlast,
            frame_length => frame_length, error_count => error_count,
            fields_valid => fields_valid
        );

    clock: process
    begin
        while not (finished or stalled) loop
            clk <= '0';
            wait for 5 ns;
            clk <= '1';
            wait for 5 ns;
        end loop;
        wait;
    end process clock;

    count: process (clk)
    begin
        if rising_edge(clk) then
            cycle <= cycle + 1;
        end if;
    end process count;

    drive: process
        file input: text open read_mode is INPUT_FILE;
        variable text_line: line;
        variable last_beat, bytes: integer;
        variable data: std_logic_vector(8 * WIDTH - 1 downto 0);
        variable frame_in: natural := 0;
        variable first: boolean := true;
    begin
        rst <= '1';
        wait until rising_edge(clk);
        wait until rising_edge(clk);
        rst <= '0';
        while not endfile(input) loop
            readline(input, text_line);
            read(text_line, last_beat);
            read(text_line, bytes);
            hread(text_line, data);
            if first then
                while frame_out < frame_in loop  -- one message in flight at a time
                    wait until rising_edge(clk);
                end loop;
            end if;
            s_tdata <= data;
            s_tkeep <= std_logic_vector(to_unsigned(2 ** bytes - 1, WIDTH));
            s_tlast <= '1' when last_beat = 1 else '0';
            s_tvalid <= '1';
            wait until rising_edge(clk) and s_tready = '1';
            first := last_beat = 1;
            if first then
                frame_in := frame_in + 1;
            end if;
            s_tvalid <= '0';
        end loop;
        while frame_out < frame_in loop
            wait until rising_edge(clk);
        end loop;
        finished <= true;
        wait;
    end process drive;

    watch: process (clk)
        file output: text open write_mode is OUTPUT_FILE;
        variable text_line: line;
        variable started: boolean := false;
        variable presented: boolean := false;
        variable quiet: natural := 0;

        -- An event's line: its name and the cycle it happened on ("start 12").
        procedure log_event(name: string) is
        begin
            write(text_line, name);
            write(text_line, cycle);
            writeline(output, text_line);
        end procedure log_event;
    begin
        if rising_edge(clk) and rst = '0' then
            quiet := quiet + 1;
            if s_tvalid = '1' and s_tready = '1' then
                quiet := 0;
                if not started then
                    log_event("start ");
                    started := true;
                end if;
                if s_tlast = '1' then
                    log_event("last ");
                end if;
            end if;
            if fields_valid = '1' and not presented then
                log_event("fields ");
                presented := true;
            end if;
            if m_tvalid = '1' then
                quiet := 0;
                write(text_line, string'("beat "));
                write(text_line, cycle);
                if m_tlast = '1' then
                    write(text_line, string'(" 1 "));
                else
                    write(text_line, string'(" 0 "));
                end if;
                hwrite(text_line, m_tkeep);
                write(text_line, string'(" "));
                hwrite(text_line, m_tdata);
                writeline(output, text_line);
                if m_tlast = '1' then
                    write(text_line, string'("end "));
                    write(text_line, cycle);
                    write(text_line, string'(" "));
                    write(text_line, to_integer(unsigned(frame_length)));
                    write(text_line, string'(" "));
                    write(text_line, to_integer(unsigned(error_count)));
                    writeline(output, text_line);
                    started := false;
                    presented := false;
                    frame_out <= frame_out + 1;
                end if;
            end if;
            if quiet = STALL_CYCLES then
                log_event("stall ");
                stalled <= true;
            end if;
        end if;
    end process watch;
end architecture files;
