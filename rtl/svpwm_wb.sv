// SPDX-License-Identifier: Apache-2.0
// svpwm_wb: svpwm_core behind a 32-bit Wishbone B4 slave: svpwm_wb_if + svpwm_mmio (svpwm_regs, generated
// from rdl/svpwm.rdl, map in docs/registers.md, + svpwm_core). Every RW register field drives a core input
// continuously; the core samples its inputs at its load points, so a write takes effect at the next
// load point (carrier valley and/or peak, CTRL.upd), never in the middle of a carrier period.
// Parameters:
//   AddrWidth - byte address width of the bus port (>= 8); addresses without a register read 0
//   MinPeriod, FreqMax, GatePol - passed to svpwm_core (GatePol is also the reset value of CTRL.pol)
//               MinPeriod defaults to the build's (svpwm_pkg::min_period(Features), as svpwm_mmio)
//   Features  - the build, a mask of svpwm_pkg::Feat* bits (default svpwm_pkg::CfgFull; svpwm_mmio):
//               registers and fields of a feature not built read 0 and ignore writes (FEATURES.features)
//   ClkHz     - the core clock in Hz, read back in CLK_HZ for host software (0 = not stated; >= 0)
//   CntWidth  - the core's carrier / period / compare width, 12..16 (default 16, the PERIOD field's);
//               a PERIOD above 2^CntWidth - 1 runs as 2^CntWidth - 1 (svpwm_mmio)
//   The other widths are fixed by the register map: PhaseWidth 34, FreqWidth 24, DtWidth 10 (change
//   rdl/svpwm.rdl and regenerate to change them).
// Latency: ACK and read data the clock after the access is accepted (pipelined: one access per
//   clock; classic: one access every two clocks).
// Restrictions: values written to several registers (e.g. V1 and V2) are sampled together only if
//   all writes land between two load points; CTRL.lock and the core's lock hold until reset.
`default_nettype none

module svpwm_wb #(
  parameter int         AddrWidth = 8,                           // byte address width (>= 8)
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,          // the build (svpwm_pkg::Cfg*)
  parameter bit         Pipelined = 1'b1,                        // 1 B4 pipelined, 0 B4 classic
  parameter int         MinPeriod = svpwm_pkg::min_period(Features),   // svpwm_core MinPeriod
  parameter int         FreqMax   = (1 << 23) - 1,               // svpwm_core FreqMax (FreqWidth 24)
  parameter logic [1:0] GatePol   = 2'b00,                       // svpwm_core GatePol, CTRL.pol reset
  parameter int         ClkHz     = 0,                           // clock in Hz, read in CLK_HZ (0 = not stated)
  parameter int         CntWidth  = 16                           // svpwm_core CntWidth, 12..16
) (
  input  logic                 clk_i,              // core and bus clock
  input  logic                 rst_ni,             // asynchronous reset, active low
  // Wishbone B4 slave (32-bit data, 8-bit granularity; ADR is a byte address, ADR[1:0] ignored)
  input  logic                 wb_cyc_i,
  input  logic                 wb_stb_i,
  input  logic                 wb_we_i,
  input  logic [AddrWidth-1:0] wb_adr_i,
  input  logic [31:0]          wb_dat_i,
  input  logic [3:0]           wb_sel_i,
  output logic [31:0]          wb_dat_o,
  output logic                 wb_ack_o,
  output logic                 wb_stall_o,         // pipelined mode; always 0
  // inverter side
  input  logic                 fault_i,            // trip input, asynchronous, active high
  input  logic                 sync_i,             // another core's sync_o (same clock), CTRL.sync_en
  output logic [2:0]           gate_hi_o,          // {c, b, a} high-side gate pins (polarity applied)
  output logic [2:0]           gate_lo_o,          // {c, b, a} low-side gate pins (polarity applied)
  output logic [2:0]           pole_o,             // {c, b, a} modulator states before dead time
  output logic                 valley_o,           // pulse: first clock of a carrier period
  output logic                 peak_o,             // pulse: carrier peak
  output logic                 update_o,           // pulse: new compare values active from this clock
  output logic                 adc_trig_o,         // pulse: ADC trigger (CTRL.adc_trig, ADC_PT0 / ADC_PT1)
  output logic [1:0]           adc_pt_o,           // pulse: ADC trigger point k (ADC_PT0 / ADC_PT1; feature adc)
  output logic                 sync_o,             // pulse at each valley, for other cores' sync_i
  output logic                 running_o,          // gates modulating (e.g. an LED)
  output logic                 tripped_o           // safe state forced (e.g. an LED)
);

  logic                 req, we;
  logic [AddrWidth-1:0] addr;
  logic [31:0]          wdata, rdata;
  logic [3:0]           be;

  svpwm_wb_if #(
    .AddrWidth (AddrWidth),
    .Pipelined (Pipelined)
  ) u_if (
    .clk_i (clk_i), .rst_ni (rst_ni),
    .wb_cyc_i (wb_cyc_i), .wb_stb_i (wb_stb_i), .wb_we_i (wb_we_i), .wb_adr_i (wb_adr_i),
    .wb_dat_i (wb_dat_i), .wb_sel_i (wb_sel_i), .wb_dat_o (wb_dat_o), .wb_ack_o (wb_ack_o),
    .wb_stall_o (wb_stall_o),
    .req_o (req), .we_o (we), .addr_o (addr), .wdata_o (wdata), .be_o (be), .rdata_i (rdata)
  );

  svpwm_mmio #(
    .Features (Features),
    .AddrWidth (AddrWidth), .MinPeriod (MinPeriod), .FreqMax (FreqMax), .GatePol (GatePol), .ClkHz (ClkHz),
    .CntWidth (CntWidth)
  ) u_mmio (
    .clk_i (clk_i), .rst_ni (rst_ni),
    .req_i (req), .we_i (we), .addr_i (addr), .wdata_i (wdata), .be_i (be), .rdata_o (rdata),
    .fault_i (fault_i), .sync_i (sync_i), .gate_hi_o (gate_hi_o), .gate_lo_o (gate_lo_o), .pole_o (pole_o),
    .valley_o (valley_o), .peak_o (peak_o), .update_o (update_o), .adc_trig_o (adc_trig_o),
    .adc_pt_o (adc_pt_o), .sync_o (sync_o), .running_o (running_o), .tripped_o (tripped_o)
  );

endmodule

`default_nettype wire
