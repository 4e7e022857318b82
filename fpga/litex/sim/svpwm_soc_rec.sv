// SPDX-License-Identifier: Apache-2.0
// svpwm_soc_rec: simulation-only recorder and fault stimulus for the LiteX SoC simulation
// (fpga/litex/svpwm_soc.py SimSoC, checked by fpga/litex/tests/test_soc_sim.py). Not synthesisable.
// Clock numbering: cycle n is the clock period after the n-th rising edge of clk_i counted from 0; every
// line is "<tag> <cycle> <values>" (decimal cycle, hex values), flushed at once:
//   G c w        gate word w = {lo[2:0], hi[2:0]} from cycle c on (the model's gate_edges word)
//   W c a d s    write of d (byte lanes s) to the core's byte offset a, in its register from cycle c on
//                (svpwm_wb Pipelined = 0: the request clock is c - 1, ACK is high in c)
//   F c v        fault pad (active high here) = v from cycle c on
//   R c v / T c v  running_o / tripped_o = v from cycle c on
//   H c          heartbeat every 65536 clocks (the log's last cycle advances while the gates are quiet)
// Plusargs: +rec=FILE (default svpwm_rec.log); +fault_after=N: the fault pad goes high N clocks after
// running_o first rises (0 = never), for +fault_len=L clocks (default 2000).
`default_nettype none
module svpwm_soc_rec (
  input  logic        clk_i,
  input  logic        rst_i,
  input  logic [2:0]  hi_i,
  input  logic [2:0]  lo_i,
  input  logic        running_i,
  input  logic        tripped_i,
  input  logic        wb_cyc_i,
  input  logic        wb_stb_i,
  input  logic        wb_we_i,
  input  logic        wb_ack_i,
  input  logic [29:0] wb_adr_i,     // word address (LiteX)
  input  logic [31:0] wb_dat_i,
  input  logic [3:0]  wb_sel_i,
  output logic        fault_o
);
  integer fd;
  longint cycle;
  longint fault_after, fault_len, fault_at;
  string  fname;
  logic [5:0] gates_q;
  logic run_q, trip_q, fault_q, seen_run;

  initial begin
    if (!$value$plusargs("rec=%s", fname)) fname = "svpwm_rec.log";
    if (!$value$plusargs("fault_after=%d", fault_after)) fault_after = 0;
    if (!$value$plusargs("fault_len=%d", fault_len)) fault_len = 2000;
    fd = $fopen(fname, "w");
    cycle = 0;
    gates_q = 6'h0;
    run_q = 1'b0;
    trip_q = 1'b0;
    fault_q = 1'b0;
    fault_o = 1'b0;
    seen_run = 1'b0;
    fault_at = 0;
  end

  // values sampled at the rising edge ending cycle `cycle`
  always @(posedge clk_i) begin
    if ({lo_i, hi_i} != gates_q) begin
      $fwrite(fd, "G %0d %02x\n", cycle, {lo_i, hi_i});
      $fflush(fd);
    end
    gates_q <= {lo_i, hi_i};
    if (running_i != run_q) begin $fwrite(fd, "R %0d %0d\n", cycle, running_i); $fflush(fd); end
    run_q <= running_i;
    if (tripped_i != trip_q) begin $fwrite(fd, "T %0d %0d\n", cycle, tripped_i); $fflush(fd); end
    trip_q <= tripped_i;
    if (fault_o != fault_q) begin $fwrite(fd, "F %0d %0d\n", cycle, fault_o); $fflush(fd); end
    fault_q <= fault_o;
    if (!rst_i && wb_cyc_i && wb_stb_i && wb_we_i && !wb_ack_i) begin
      $fwrite(fd, "W %0d %02x %08x %1x\n", cycle + 1, {wb_adr_i[5:0], 2'b00}, wb_dat_i, wb_sel_i);
      $fflush(fd);
    end
    // fault stimulus: changes right after this edge, i.e. from cycle + 1 on
    if (fault_after != 0 && running_i && !seen_run) begin
      seen_run <= 1'b1;
      fault_at <= cycle + fault_after;
    end
    if (seen_run && fault_at != 0 && cycle + 1 == fault_at) fault_o <= 1'b1;
    if (seen_run && fault_at != 0 && cycle + 1 == fault_at + fault_len) fault_o <= 1'b0;
    if (cycle[15:0] == 16'hffff) begin $fwrite(fd, "H %0d\n", cycle); $fflush(fd); end
    cycle <= cycle + 1;
  end
endmodule
`default_nettype wire
