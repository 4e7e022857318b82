// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_fusesoc: the self-checking testbench of svpwm.core's `sim` target (Icarus through edalize).
// svpwm_mmio with its parameters at their defaults but Features: after reset the register port reads ID,
// CTRL's reset value and FEATURES (the build) and the gates stay off; prints "tb_svpwm_fusesoc: PASS" or
// stops with $fatal.
// Parameters: Features - svpwm_mmio's (svpwm.core's parameter Features; default svpwm_pkg::CfgFull).
// Restrictions: simulation only.
`default_nettype none

module tb_svpwm_fusesoc #(
  parameter int Features = 32'h7fff        // svpwm_pkg::CfgFull (int: FuseSoC passes an integer)
);
  logic        clk = 1'b0, rst_n = 1'b0, req = 1'b0;
  logic [7:0]  addr = '0;
  logic [31:0] rdata;
  logic [2:0]  gate_hi, gate_lo;

  always #5 clk = ~clk;

  svpwm_mmio #(.Features (32'(Features))) u_dut (
    .clk_i (clk), .rst_ni (rst_n), .req_i (req), .we_i (1'b0), .addr_i (addr), .wdata_i (32'h0),
    .be_i (4'hf), .rdata_o (rdata), .fault_i (1'b0), .sync_i (1'b0), .gate_hi_o (gate_hi),
    .gate_lo_o (gate_lo), .pole_o (), .valley_o (), .peak_o (), .update_o (), .adc_trig_o (),
    .adc_pt_o (), .sync_o (), .running_o (), .tripped_o ()
  );

  task automatic check_read(input logic [7:0] a, input logic [31:0] exp);
    @(negedge clk); req = 1'b1; addr = a;
    @(negedge clk); req = 1'b0;
    if (rdata !== exp) $fatal(1, "tb_svpwm_fusesoc: read 0x%02h = 0x%08h, expected 0x%08h", a, rdata, exp);
  endtask

  initial begin
    repeat (3) @(negedge clk);
    rst_n = 1'b1;
    check_read(8'h00, 32'h5356_5057);            // ID "SVPW"
    check_read(8'h0c, 32'h0000_0000);            // CTRL reset value (GatePol = 0)
    check_read(8'h5c, {16'h0, 16'(Features)});   // FEATURES: the build, no board cut
    if (gate_hi !== 3'b000 || gate_lo !== 3'b000) $fatal(1, "tb_svpwm_fusesoc: gates on while stopped");
    $display("tb_svpwm_fusesoc: PASS");
    $finish;
  end
endmodule

`default_nettype wire
