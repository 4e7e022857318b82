// SPDX-License-Identifier: Apache-2.0
// Test harness: the full bus wrappers (Bus = 0 svpwm_axil, 1 svpwm_wb pipelined, 2 svpwm_wb classic)
// with port names for cocotbext-axi ("s_axil_*") and cocotbext-wishbone ("wb_*"). The core is probed
// hierarchically (gen_axil.u_dut.u_mmio.u_core / gen_wb.u_dut.u_mmio.u_core). Clock generated here.
// Features: the wrappers' build (int: -G / -P pass 32-bit values; default svpwm_pkg::CfgFull).
`timescale 1ns/1ps
`default_nettype none

module tb_svpwm_bus #(
  parameter int Bus       = 0,
  parameter int AddrWidth = 8,
  parameter int MinPeriod = svpwm_pkg::min_period(svpwm_pkg::CfgFull),
  parameter int ClkHz     = 0,
  parameter int CntWidth  = 16,
  parameter int Features  = 32'h7fff
) (
  input  wire logic                 rst_n,
  input  wire logic [AddrWidth-1:0] s_axil_awaddr,
  input  wire logic                 s_axil_awvalid,
  output      logic                 s_axil_awready,
  input  wire logic [31:0]          s_axil_wdata,
  input  wire logic [3:0]           s_axil_wstrb,
  input  wire logic                 s_axil_wvalid,
  output      logic                 s_axil_wready,
  output      logic [1:0]           s_axil_bresp,
  output      logic                 s_axil_bvalid,
  input  wire logic                 s_axil_bready,
  input  wire logic [AddrWidth-1:0] s_axil_araddr,
  input  wire logic                 s_axil_arvalid,
  output      logic                 s_axil_arready,
  output      logic [31:0]          s_axil_rdata,
  output      logic [1:0]           s_axil_rresp,
  output      logic                 s_axil_rvalid,
  input  wire logic                 s_axil_rready,
  input  wire logic                 wb_cyc,
  input  wire logic                 wb_stb,
  input  wire logic                 wb_we,
  input  wire logic [AddrWidth-1:0] wb_adr,
  input  wire logic [31:0]          wb_datwr,
  input  wire logic [3:0]           wb_sel,
  output      logic [31:0]          wb_datrd,
  output      logic                 wb_ack,
  output      logic                 wb_stall,
  input  wire logic                 fault,
  input  wire logic                 sync_in,
  output      logic [2:0]           gate_hi,
  output      logic [2:0]           gate_lo,
  output      logic [2:0]           pole,
  output      logic                 valley,
  output      logic                 peak,
  output      logic                 update,
  output      logic                 adc_trig,
  output      logic [1:0]           adc_pt,
  output      logic                 sync_out,
  output      logic                 running,
  output      logic                 tripped
);
  logic clk;
  initial clk = 1'b0;
  always #5 clk = ~clk;

  if (Bus == 0) begin : gen_axil
    svpwm_axil #(.AddrWidth(AddrWidth), .MinPeriod(MinPeriod), .ClkHz(ClkHz), .CntWidth(CntWidth),
                 .Features(32'(Features))) u_dut (
      .clk_i(clk), .rst_ni(rst_n),
      .axil_awaddr_i(s_axil_awaddr), .axil_awvalid_i(s_axil_awvalid), .axil_awready_o(s_axil_awready),
      .axil_wdata_i(s_axil_wdata), .axil_wstrb_i(s_axil_wstrb), .axil_wvalid_i(s_axil_wvalid),
      .axil_wready_o(s_axil_wready), .axil_bresp_o(s_axil_bresp), .axil_bvalid_o(s_axil_bvalid),
      .axil_bready_i(s_axil_bready), .axil_araddr_i(s_axil_araddr), .axil_arvalid_i(s_axil_arvalid),
      .axil_arready_o(s_axil_arready), .axil_rdata_o(s_axil_rdata), .axil_rresp_o(s_axil_rresp),
      .axil_rvalid_o(s_axil_rvalid), .axil_rready_i(s_axil_rready),
      .fault_i(fault), .sync_i(sync_in), .gate_hi_o(gate_hi), .gate_lo_o(gate_lo), .pole_o(pole),
      .valley_o(valley), .peak_o(peak), .update_o(update), .adc_trig_o(adc_trig), .adc_pt_o(adc_pt),
      .sync_o(sync_out),
      .running_o(running), .tripped_o(tripped));
    assign wb_datrd = '0;
    assign wb_ack   = 1'b0;
    assign wb_stall = 1'b0;
  end else begin : gen_wb
    svpwm_wb #(.AddrWidth(AddrWidth), .Pipelined(Bus == 1), .MinPeriod(MinPeriod), .ClkHz(ClkHz),
               .CntWidth(CntWidth), .Features(32'(Features))) u_dut (
      .clk_i(clk), .rst_ni(rst_n),
      .wb_cyc_i(wb_cyc), .wb_stb_i(wb_stb), .wb_we_i(wb_we), .wb_adr_i(wb_adr), .wb_dat_i(wb_datwr),
      .wb_sel_i(wb_sel), .wb_dat_o(wb_datrd), .wb_ack_o(wb_ack), .wb_stall_o(wb_stall),
      .fault_i(fault), .sync_i(sync_in), .gate_hi_o(gate_hi), .gate_lo_o(gate_lo), .pole_o(pole),
      .valley_o(valley), .peak_o(peak), .update_o(update), .adc_trig_o(adc_trig), .adc_pt_o(adc_pt),
      .sync_o(sync_out),
      .running_o(running), .tripped_o(tripped));
    assign s_axil_awready = 1'b0;
    assign s_axil_wready  = 1'b0;
    assign s_axil_bresp   = 2'b00;
    assign s_axil_bvalid  = 1'b0;
    assign s_axil_arready = 1'b0;
    assign s_axil_rdata   = '0;
    assign s_axil_rresp   = 2'b00;
    assign s_axil_rvalid  = 1'b0;
  end
endmodule

`default_nettype wire
