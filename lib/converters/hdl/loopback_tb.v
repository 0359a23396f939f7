// Testbench for rfc_loopback (rfc.lib.converters.loopback) in Verilog, for Verilator: the same
// files and events, on the same cycles, as loopback_tb.vhd (see its header). The files are
// given as plusargs, +input=PATH and +output=PATH, so one compiled model serves every run.
`timescale 1ns/1ps

module rfc_loopback_tb;
    parameter WIDTH = 8;
    parameter STALL_CYCLES = 100000;

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg [8 * WIDTH - 1:0] s_tdata = 0;
    reg [WIDTH - 1:0] s_tkeep = 0;
    reg s_tvalid = 1'b0;
    reg s_tlast = 1'b0;
    wire s_tready;
    wire [8 * WIDTH - 1:0] m_tdata;
    wire [WIDTH - 1:0] m_tkeep;
    wire m_tvalid, m_tlast;
    wire [31:0] frame_length, error_count;
    wire fields_valid;
    integer cycle = 0;
    integer frame_out = 0;
    integer frame_in = 0;
    integer output_file;

    rfc_loopback dut (
        .clk(clk), .rst(rst),
        .s_axis_tdata(s_tdata), .s_axis_tkeep(s_tkeep), .s_axis_tvalid(s_tvalid),
        .s_axis_tready(s_tready), .s_axis_tlast(s_tlast),
        .m_axis_tdata(m_tdata), .m_axis_tkeep(m_tkeep), .m_axis_tvalid(m_tvalid),
        .m_axis_tready(1'b1), .m_axis_tlast(m_tlast),
        .frame_length(frame_length), .error_count(error_count),
        .fields_valid(fields_valid)
    );

    always #5 clk = ~clk;

    always @(posedge clk) cycle <= cycle + 1;

    reg [8 * 1024 - 1:0] input_path, output_path;
    integer input_file, last_beat, bytes, code;
    reg [8 * WIDTH - 1:0] data;
    reg first;

    initial begin
        if (!$value$plusargs("input=%s", input_path)
                || !$value$plusargs("output=%s", output_path)) begin
            $display("usage: +input=PATH +output=PATH");
            $finish;
        end
        input_file = $fopen(input_path, "r");
        output_file = $fopen(output_path, "w");
        first = 1'b1;
        rst <= 1'b1;
        @(posedge clk);
        @(posedge clk);
        rst <= 1'b0;
        while (!$feof(input_file)) begin
            code = $fscanf(input_file, "%d %d %h\n", last_beat, bytes, data);
            if (code == 3) begin
                if (first) begin
                    while (frame_out < frame_in) @(posedge clk);  // one message in flight
                end
                s_tdata <= data;
                s_tkeep <= (1 << bytes) - 1;
                s_tlast <= last_beat == 1;
                s_tvalid <= 1'b1;
                @(posedge clk);
                while (!s_tready) @(posedge clk);
                first = last_beat == 1;
                if (first) frame_in = frame_in + 1;
                s_tvalid <= 1'b0;
            end
        end
        while (frame_out < frame_in) @(posedge clk);
        $fclose(output_file);
        $finish;
    end

    reg started = 1'b0;
    reg presented = 1'b0;
    integer quiet = 0;

    always @(posedge clk) begin
        if (!rst) begin
            quiet = quiet + 1;
            if (s_tvalid && s_tready) begin
                quiet = 0;
                if (!started) begin
                    $fwrite(output_file, "start %0d\n", cycle);
                    started = 1'b1;
                end
                if (s_tlast) $fwrite(output_file, "last %0d\n", cycle);
            end
            if (fields_valid && !presented) begin
                $fwrite(output_file, "fields %0d\n", cycle);
                presented = 1'b1;
            end
            if (m_tvalid) begin
                quiet = 0;
                $fwrite(output_file, "beat %0d %0d %h %h\n", cycle, m_tlast, m_tkeep, m_tdata);
                if (m_tlast) begin
                    $fwrite(output_file, "end %0d %0d %0d\n", cycle, frame_length, error_count);
                    started = 1'b0;
                    presented = 1'b0;
                    frame_out <= frame_out + 1;
                end
            end
            if (quiet == STALL_CYCLES) begin
                $fwrite(output_file, "stall %0d\n", cycle);
                $fclose(output_file);
                $finish;
            end
        end
    end
endmodule
