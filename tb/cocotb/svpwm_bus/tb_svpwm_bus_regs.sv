// SPDX-License-Identifier: Apache-2.0
// Test harness: one bus adapter (Bus = 0 AXI4-Lite, 1 Wishbone pipelined, 2 Wishbone classic) + the
// generated register block (the build Features, the board cut Trim), without the core: the register
// outputs are harness outputs and the status inputs harness inputs, so that cocotb sees and drives
// every field. Port names follow the cocotbext-axi ("s_axil_*") and cocotbext-wishbone ("wb_*")
// conventions. Clock generated here.
`timescale 1ns/1ps
`default_nettype none

module tb_svpwm_bus_regs #(
  parameter int         Bus       = 0,
  parameter int         AddrWidth = 8,
  parameter int         GatePol   = 0,      // int here: -G / -P pass 32-bit values
  parameter int         ClkHz     = 0,      // CLK_HZ value
  parameter int         Features  = 32'h7fff, // the build (svpwm_pkg::Cfg*; int: -G / -P)
  parameter int         Trim      = 0       // 1: the board cut of the register block
) (
  input  wire logic                 rst_n,
  // AXI4-Lite (Bus = 0)
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
  // Wishbone (Bus = 1, 2)
  input  wire logic                 wb_cyc,
  input  wire logic                 wb_stb,
  input  wire logic                 wb_we,
  input  wire logic [AddrWidth-1:0] wb_adr,
  input  wire logic [31:0]          wb_datwr,
  input  wire logic [3:0]           wb_sel,
  output      logic [31:0]          wb_datrd,
  output      logic                 wb_ack,
  output      logic                 wb_stall,
  // status inputs of the register block (driven by cocotb)
  input  wire logic [10:0]          status,     // {sector[2:0], locked, tripped, fault, freq_clamp,
                                                //  period_clamp, cfg_err, sat, running}
  input  wire logic [16:0]          carrier,    // {up, count}
  input  wire logic [15:0]          period_act,
  input  wire logic [47:0]          cmp,        // {C_c, C_b, C_a}
  input  wire logic [50:0]          win_lo,     // {c, b, a} 17 bits each (WIN_LO_*)
  input  wire logic [50:0]          win_hi,     // {c, b, a} 17 bits each (WIN_HI_*)
  input  wire logic [4:0]           win_st      // {recon[1:0], ok[2:0]} (WIN_STATUS)
);
  logic clk;
  initial clk = 1'b0;
  always #5 clk = ~clk;

  logic                 req, we;
  logic [AddrWidth-1:0] addr;
  logic [31:0]          wdata, rdata;
  logic [3:0]           be;

  if (Bus == 0) begin : gen_axil
    svpwm_axil_if #(.AddrWidth(AddrWidth)) u_if (
      .clk_i(clk), .rst_ni(rst_n),
      .axil_awaddr_i(s_axil_awaddr), .axil_awvalid_i(s_axil_awvalid), .axil_awready_o(s_axil_awready),
      .axil_wdata_i(s_axil_wdata), .axil_wstrb_i(s_axil_wstrb), .axil_wvalid_i(s_axil_wvalid),
      .axil_wready_o(s_axil_wready), .axil_bresp_o(s_axil_bresp), .axil_bvalid_o(s_axil_bvalid),
      .axil_bready_i(s_axil_bready), .axil_araddr_i(s_axil_araddr), .axil_arvalid_i(s_axil_arvalid),
      .axil_arready_o(s_axil_arready), .axil_rdata_o(s_axil_rdata), .axil_rresp_o(s_axil_rresp),
      .axil_rvalid_o(s_axil_rvalid), .axil_rready_i(s_axil_rready),
      .req_o(req), .we_o(we), .addr_o(addr), .wdata_o(wdata), .be_o(be), .rdata_i(rdata));
    assign wb_datrd = '0;
    assign wb_ack   = 1'b0;
    assign wb_stall = 1'b0;
  end else begin : gen_wb
    svpwm_wb_if #(.AddrWidth(AddrWidth), .Pipelined(Bus == 1)) u_if (
      .clk_i(clk), .rst_ni(rst_n),
      .wb_cyc_i(wb_cyc), .wb_stb_i(wb_stb), .wb_we_i(wb_we), .wb_adr_i(wb_adr), .wb_dat_i(wb_datwr),
      .wb_sel_i(wb_sel), .wb_dat_o(wb_datrd), .wb_ack_o(wb_ack), .wb_stall_o(wb_stall),
      .req_o(req), .we_o(we), .addr_o(addr), .wdata_o(wdata), .be_o(be), .rdata_i(rdata));
    assign s_axil_awready = 1'b0;
    assign s_axil_wready  = 1'b0;
    assign s_axil_bresp   = 2'b00;
    assign s_axil_bvalid  = 1'b0;
    assign s_axil_arready = 1'b0;
    assign s_axil_rdata   = '0;
    assign s_axil_rresp   = 2'b00;
    assign s_axil_rvalid  = 1'b0;
  end

  // register outputs, probed by cocotb as u_regs.<name>_o
  svpwm_regs #(.AddrWidth(AddrWidth), .GatePol(2'(GatePol)), .ClkHz(ClkHz), .Features(32'(Features)),
              .Trim(1'(Trim))) u_regs (
    .clk_i(clk), .rst_ni(rst_n), .req_i(req), .we_i(we), .addr_i(addr), .wdata_i(wdata), .be_i(be),
    .rdata_o(rdata),
    .ctrl_en_o(), .ctrl_sync_en_o(), .ctrl_trip_cbc_o(), .ctrl_safe_lo_o(), .ctrl_pol_o(), .ctrl_lock_o(),
    .ctrl_fault_clear_o(), .ctrl_mode_o(), .ctrl_upd_o(), .ctrl_dpwm_o(), .ctrl_om_o(), .ctrl_vsc_off_o(),
    .ctrl_adc_trig_o(),
    .freq_o(), .m_o(), .theta_o(), .v1_o(), .v2_o(), .vf_boost_o(), .vf_slope_o(), .vf_mmax_o(),
    .period_o(), .dt_dt_o(), .dt_dtf_o(), .dt_dtf_en_o(), .mp_o(), .presc_o(), .dtc_en_o(), .dtc_isign_o(),
    .adc_pt0_cnt_o(), .adc_pt0_dn_o(), .adc_pt0_en_o(), .adc_pt1_cnt_o(), .adc_pt1_dn_o(), .adc_pt1_en_o(),
    .win_min_o(),
    .status_running_i(status[0]), .status_sat_i(status[1]), .status_cfg_err_i(status[2]),
    .status_period_clamp_i(status[3]), .status_freq_clamp_i(status[4]), .status_fault_i(status[5]),
    .status_tripped_i(status[6]), .status_locked_i(status[7]), .status_sector_i(status[10:8]),
    .carrier_count_i(carrier[15:0]), .carrier_up_i(carrier[16]), .period_act_i(period_act),
    .cmp_a_i(cmp[15:0]), .cmp_b_i(cmp[31:16]), .cmp_c_i(cmp[47:32]),
    .win_lo_a_i(win_lo[16:0]), .win_lo_b_i(win_lo[33:17]), .win_lo_c_i(win_lo[50:34]),
    .win_hi_a_i(win_hi[16:0]), .win_hi_b_i(win_hi[33:17]), .win_hi_c_i(win_hi[50:34]),
    .win_status_ok_i(win_st[2:0]), .win_status_recon_i(win_st[4:3]));
endmodule

`default_nettype wire
