set title 'stiff sine-Gordon, κ = 100: erkn''s explicit methods + peers — error vs CPU time' noenhanced
set xlabel 'CPU time (s)'
set ylabel 'max-norm error of q at t = 1'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'stiff_k100_explicit_cpu.png'
plot 'data/stiff_k100_strang.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/stiff_k100_yoshida4.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/stiff_k100_saba2.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/stiff_k100_saba3.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/stiff_k100_saba4.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/stiff_k100_srkn6b.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/stiff_k100_aba864.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/stiff_k100_aba1064.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/stiff_k100_abah864.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/stiff_k100_srkn11b.dat' u 5:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/stiff_k100_srkn14a.dat' u 5:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/stiff_k100_sd9_10_6_4.dat' u 5:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/stiff_k100_sdt7_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/stiff_k100_sdt7x_4.dat' u 5:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/stiff_k100_chinc.dat' u 5:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/stiff_k100_omf4_3f3g.dat' u 5:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/stiff_k100_omf6_5f3g.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/stiff_k100_omf8_11f11g.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/stiff_k100_sabac1.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/stiff_k100_sabac2.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/stiff_k100_sabac3.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/stiff_k100_sabac4.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/stiff_k100_pmlf4.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/stiff_k100_pmlf6.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/stiff_k100_plf7_6_4.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/stiff_k100_st_rmer_verlet.dat' u 5:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/stiff_k100_odeint_sb3a_mclachlan.dat' u 5:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/stiff_k100_odeint_sb3a_m4_mclachlan.dat' u 5:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/stiff_k100_gauss2_order_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/stiff_k100_strang_impulse.dat' u 5:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/stiff_k100_blanes_moan_srkn6b.dat' u 5:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/stiff_k100_blanes_moan_srkn14a.dat' u 5:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/stiff_k100_aba_10_6_4.dat' u 5:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/stiff_k100_mollified_impulse_sinc.dat' u 5:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/stiff_k100_omf4_4mn3f3gp.dat' u 5:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/stiff_k100_pmlf6_processed.dat' u 5:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'stiff_k100_explicit_cpu.svg'
plot 'data/stiff_k100_strang.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/stiff_k100_yoshida4.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/stiff_k100_saba2.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/stiff_k100_saba3.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/stiff_k100_saba4.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/stiff_k100_srkn6b.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/stiff_k100_aba864.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/stiff_k100_aba1064.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/stiff_k100_abah864.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/stiff_k100_srkn11b.dat' u 5:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/stiff_k100_srkn14a.dat' u 5:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/stiff_k100_sd9_10_6_4.dat' u 5:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/stiff_k100_sdt7_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/stiff_k100_sdt7x_4.dat' u 5:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/stiff_k100_chinc.dat' u 5:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/stiff_k100_omf4_3f3g.dat' u 5:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/stiff_k100_omf6_5f3g.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/stiff_k100_omf8_11f11g.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/stiff_k100_sabac1.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/stiff_k100_sabac2.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/stiff_k100_sabac3.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/stiff_k100_sabac4.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/stiff_k100_pmlf4.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/stiff_k100_pmlf6.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/stiff_k100_plf7_6_4.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/stiff_k100_st_rmer_verlet.dat' u 5:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/stiff_k100_odeint_sb3a_mclachlan.dat' u 5:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/stiff_k100_odeint_sb3a_m4_mclachlan.dat' u 5:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/stiff_k100_gauss2_order_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/stiff_k100_strang_impulse.dat' u 5:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/stiff_k100_blanes_moan_srkn6b.dat' u 5:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/stiff_k100_blanes_moan_srkn14a.dat' u 5:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/stiff_k100_aba_10_6_4.dat' u 5:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/stiff_k100_mollified_impulse_sinc.dat' u 5:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/stiff_k100_omf4_4mn3f3gp.dat' u 5:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/stiff_k100_pmlf6_processed.dat' u 5:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
unset output
set title 'stiff sine-Gordon, κ = 100: erkn''s explicit methods + peers — error vs h (×: failed; ▼: S(0, z) bound)' noenhanced
set xlabel 'step size h'
set ylabel 'max-norm error of q at t = 1'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set yrange [:3e4]
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'stiff_k100_explicit_h.png'
plot 'data/stiff_k100_strang.dat' u 2:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', 'data/stiff_k100_strang_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_strang_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_yoshida4.dat' u 2:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', 'data/stiff_k100_yoshida4_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_yoshida4_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba2.dat' u 2:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', 'data/stiff_k100_saba2_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba2_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba3.dat' u 2:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', 'data/stiff_k100_saba3_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba3_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba4.dat' u 2:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', 'data/stiff_k100_saba4_failed.dat' u 2:(1e3) w p lc rgb '#ff7f0e' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba4_predicted.dat' u 1:(1e4) w p lc rgb '#ff7f0e' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn6b.dat' u 2:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', 'data/stiff_k100_srkn6b_failed.dat' u 2:(1e3) w p lc rgb '#8c564b' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn6b_predicted.dat' u 1:(1e4) w p lc rgb '#8c564b' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba864.dat' u 2:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', 'data/stiff_k100_aba864_failed.dat' u 2:(1e3) w p lc rgb '#e377c2' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba864_predicted.dat' u 1:(1e4) w p lc rgb '#e377c2' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba1064.dat' u 2:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', 'data/stiff_k100_aba1064_failed.dat' u 2:(1e3) w p lc rgb '#17becf' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba1064_predicted.dat' u 1:(1e4) w p lc rgb '#17becf' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_abah864.dat' u 2:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', 'data/stiff_k100_abah864_failed.dat' u 2:(1e3) w p lc rgb '#7f7f7f' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_abah864_predicted.dat' u 1:(1e4) w p lc rgb '#7f7f7f' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn11b.dat' u 2:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', 'data/stiff_k100_srkn11b_failed.dat' u 2:(1e3) w p lc rgb '#bcbd22' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn11b_predicted.dat' u 1:(1e4) w p lc rgb '#bcbd22' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn14a.dat' u 2:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', 'data/stiff_k100_srkn14a_failed.dat' u 2:(1e3) w p lc rgb '#393b79' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn14a_predicted.dat' u 1:(1e4) w p lc rgb '#393b79' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sd9_10_6_4.dat' u 2:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', 'data/stiff_k100_sd9_10_6_4_failed.dat' u 2:(1e3) w p lc rgb '#637939' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sd9_10_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#637939' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sdt7_4.dat' u 2:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', 'data/stiff_k100_sdt7_4_failed.dat' u 2:(1e3) w p lc rgb '#8c6d31' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sdt7_4_predicted.dat' u 1:(1e4) w p lc rgb '#8c6d31' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sdt7x_4.dat' u 2:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', 'data/stiff_k100_sdt7x_4_failed.dat' u 2:(1e3) w p lc rgb '#843c39' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sdt7x_4_predicted.dat' u 1:(1e4) w p lc rgb '#843c39' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_chinc.dat' u 2:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', 'data/stiff_k100_chinc_failed.dat' u 2:(1e3) w p lc rgb '#7b4173' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_chinc_predicted.dat' u 1:(1e4) w p lc rgb '#7b4173' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf4_3f3g.dat' u 2:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', 'data/stiff_k100_omf4_3f3g_failed.dat' u 2:(1e3) w p lc rgb '#000000' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf4_3f3g_predicted.dat' u 1:(1e4) w p lc rgb '#000000' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf6_5f3g.dat' u 2:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', 'data/stiff_k100_omf6_5f3g_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf6_5f3g_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf8_11f11g.dat' u 2:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', 'data/stiff_k100_omf8_11f11g_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf8_11f11g_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac1.dat' u 2:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', 'data/stiff_k100_sabac1_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac1_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac2.dat' u 2:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', 'data/stiff_k100_sabac2_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac2_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac3.dat' u 2:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', 'data/stiff_k100_sabac3_failed.dat' u 2:(1e3) w p lc rgb '#ff7f0e' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac3_predicted.dat' u 1:(1e4) w p lc rgb '#ff7f0e' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac4.dat' u 2:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', 'data/stiff_k100_sabac4_failed.dat' u 2:(1e3) w p lc rgb '#8c564b' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac4_predicted.dat' u 1:(1e4) w p lc rgb '#8c564b' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf4.dat' u 2:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', 'data/stiff_k100_pmlf4_failed.dat' u 2:(1e3) w p lc rgb '#e377c2' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf4_predicted.dat' u 1:(1e4) w p lc rgb '#e377c2' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf6.dat' u 2:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', 'data/stiff_k100_pmlf6_failed.dat' u 2:(1e3) w p lc rgb '#17becf' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf6_predicted.dat' u 1:(1e4) w p lc rgb '#17becf' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_plf7_6_4.dat' u 2:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', 'data/stiff_k100_plf7_6_4_failed.dat' u 2:(1e3) w p lc rgb '#7f7f7f' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_plf7_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#7f7f7f' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_st_rmer_verlet.dat' u 2:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', 'data/stiff_k100_st_rmer_verlet_failed.dat' u 2:(1e3) w p lc rgb '#bcbd22' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_st_rmer_verlet_predicted.dat' u 1:(1e4) w p lc rgb '#bcbd22' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_odeint_sb3a_mclachlan.dat' u 2:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', 'data/stiff_k100_odeint_sb3a_mclachlan_failed.dat' u 2:(1e3) w p lc rgb '#393b79' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_odeint_sb3a_mclachlan_predicted.dat' u 1:(1e4) w p lc rgb '#393b79' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_odeint_sb3a_m4_mclachlan.dat' u 2:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', 'data/stiff_k100_odeint_sb3a_m4_mclachlan_failed.dat' u 2:(1e3) w p lc rgb '#637939' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_odeint_sb3a_m4_mclachlan_predicted.dat' u 1:(1e4) w p lc rgb '#637939' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_gauss2_order_4.dat' u 2:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', 'data/stiff_k100_gauss2_order_4_failed.dat' u 2:(1e3) w p lc rgb '#8c6d31' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_gauss2_order_4_predicted.dat' u 1:(1e4) w p lc rgb '#8c6d31' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_strang_impulse.dat' u 2:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', 'data/stiff_k100_strang_impulse_failed.dat' u 2:(1e3) w p lc rgb '#843c39' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_strang_impulse_predicted.dat' u 1:(1e4) w p lc rgb '#843c39' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_blanes_moan_srkn6b.dat' u 2:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', 'data/stiff_k100_blanes_moan_srkn6b_failed.dat' u 2:(1e3) w p lc rgb '#7b4173' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_blanes_moan_srkn6b_predicted.dat' u 1:(1e4) w p lc rgb '#7b4173' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_blanes_moan_srkn14a.dat' u 2:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', 'data/stiff_k100_blanes_moan_srkn14a_failed.dat' u 2:(1e3) w p lc rgb '#000000' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_blanes_moan_srkn14a_predicted.dat' u 1:(1e4) w p lc rgb '#000000' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba_10_6_4.dat' u 2:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', 'data/stiff_k100_aba_10_6_4_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba_10_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_mollified_impulse_sinc.dat' u 2:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', 'data/stiff_k100_mollified_impulse_sinc_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_mollified_impulse_sinc_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf4_4mn3f3gp.dat' u 2:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', 'data/stiff_k100_omf4_4mn3f3gp_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf4_4mn3f3gp_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf6_processed.dat' u 2:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)', 'data/stiff_k100_pmlf6_processed_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf6_processed_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'stiff_k100_explicit_h.svg'
plot 'data/stiff_k100_strang.dat' u 2:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', 'data/stiff_k100_strang_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_strang_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_yoshida4.dat' u 2:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', 'data/stiff_k100_yoshida4_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_yoshida4_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba2.dat' u 2:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', 'data/stiff_k100_saba2_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba2_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba3.dat' u 2:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', 'data/stiff_k100_saba3_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba3_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_saba4.dat' u 2:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', 'data/stiff_k100_saba4_failed.dat' u 2:(1e3) w p lc rgb '#ff7f0e' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_saba4_predicted.dat' u 1:(1e4) w p lc rgb '#ff7f0e' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn6b.dat' u 2:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', 'data/stiff_k100_srkn6b_failed.dat' u 2:(1e3) w p lc rgb '#8c564b' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn6b_predicted.dat' u 1:(1e4) w p lc rgb '#8c564b' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba864.dat' u 2:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', 'data/stiff_k100_aba864_failed.dat' u 2:(1e3) w p lc rgb '#e377c2' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba864_predicted.dat' u 1:(1e4) w p lc rgb '#e377c2' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba1064.dat' u 2:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', 'data/stiff_k100_aba1064_failed.dat' u 2:(1e3) w p lc rgb '#17becf' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba1064_predicted.dat' u 1:(1e4) w p lc rgb '#17becf' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_abah864.dat' u 2:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', 'data/stiff_k100_abah864_failed.dat' u 2:(1e3) w p lc rgb '#7f7f7f' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_abah864_predicted.dat' u 1:(1e4) w p lc rgb '#7f7f7f' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn11b.dat' u 2:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', 'data/stiff_k100_srkn11b_failed.dat' u 2:(1e3) w p lc rgb '#bcbd22' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn11b_predicted.dat' u 1:(1e4) w p lc rgb '#bcbd22' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_srkn14a.dat' u 2:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', 'data/stiff_k100_srkn14a_failed.dat' u 2:(1e3) w p lc rgb '#393b79' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_srkn14a_predicted.dat' u 1:(1e4) w p lc rgb '#393b79' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sd9_10_6_4.dat' u 2:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', 'data/stiff_k100_sd9_10_6_4_failed.dat' u 2:(1e3) w p lc rgb '#637939' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sd9_10_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#637939' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sdt7_4.dat' u 2:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', 'data/stiff_k100_sdt7_4_failed.dat' u 2:(1e3) w p lc rgb '#8c6d31' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sdt7_4_predicted.dat' u 1:(1e4) w p lc rgb '#8c6d31' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sdt7x_4.dat' u 2:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', 'data/stiff_k100_sdt7x_4_failed.dat' u 2:(1e3) w p lc rgb '#843c39' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sdt7x_4_predicted.dat' u 1:(1e4) w p lc rgb '#843c39' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_chinc.dat' u 2:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', 'data/stiff_k100_chinc_failed.dat' u 2:(1e3) w p lc rgb '#7b4173' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_chinc_predicted.dat' u 1:(1e4) w p lc rgb '#7b4173' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf4_3f3g.dat' u 2:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', 'data/stiff_k100_omf4_3f3g_failed.dat' u 2:(1e3) w p lc rgb '#000000' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf4_3f3g_predicted.dat' u 1:(1e4) w p lc rgb '#000000' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf6_5f3g.dat' u 2:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', 'data/stiff_k100_omf6_5f3g_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf6_5f3g_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf8_11f11g.dat' u 2:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', 'data/stiff_k100_omf8_11f11g_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf8_11f11g_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac1.dat' u 2:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', 'data/stiff_k100_sabac1_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac1_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac2.dat' u 2:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', 'data/stiff_k100_sabac2_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac2_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac3.dat' u 2:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', 'data/stiff_k100_sabac3_failed.dat' u 2:(1e3) w p lc rgb '#ff7f0e' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac3_predicted.dat' u 1:(1e4) w p lc rgb '#ff7f0e' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_sabac4.dat' u 2:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', 'data/stiff_k100_sabac4_failed.dat' u 2:(1e3) w p lc rgb '#8c564b' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_sabac4_predicted.dat' u 1:(1e4) w p lc rgb '#8c564b' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf4.dat' u 2:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', 'data/stiff_k100_pmlf4_failed.dat' u 2:(1e3) w p lc rgb '#e377c2' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf4_predicted.dat' u 1:(1e4) w p lc rgb '#e377c2' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf6.dat' u 2:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', 'data/stiff_k100_pmlf6_failed.dat' u 2:(1e3) w p lc rgb '#17becf' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf6_predicted.dat' u 1:(1e4) w p lc rgb '#17becf' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_plf7_6_4.dat' u 2:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', 'data/stiff_k100_plf7_6_4_failed.dat' u 2:(1e3) w p lc rgb '#7f7f7f' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_plf7_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#7f7f7f' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_st_rmer_verlet.dat' u 2:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', 'data/stiff_k100_st_rmer_verlet_failed.dat' u 2:(1e3) w p lc rgb '#bcbd22' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_st_rmer_verlet_predicted.dat' u 1:(1e4) w p lc rgb '#bcbd22' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_odeint_sb3a_mclachlan.dat' u 2:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', 'data/stiff_k100_odeint_sb3a_mclachlan_failed.dat' u 2:(1e3) w p lc rgb '#393b79' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_odeint_sb3a_mclachlan_predicted.dat' u 1:(1e4) w p lc rgb '#393b79' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_odeint_sb3a_m4_mclachlan.dat' u 2:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', 'data/stiff_k100_odeint_sb3a_m4_mclachlan_failed.dat' u 2:(1e3) w p lc rgb '#637939' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_odeint_sb3a_m4_mclachlan_predicted.dat' u 1:(1e4) w p lc rgb '#637939' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_gauss2_order_4.dat' u 2:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', 'data/stiff_k100_gauss2_order_4_failed.dat' u 2:(1e3) w p lc rgb '#8c6d31' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_gauss2_order_4_predicted.dat' u 1:(1e4) w p lc rgb '#8c6d31' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_strang_impulse.dat' u 2:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', 'data/stiff_k100_strang_impulse_failed.dat' u 2:(1e3) w p lc rgb '#843c39' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_strang_impulse_predicted.dat' u 1:(1e4) w p lc rgb '#843c39' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_blanes_moan_srkn6b.dat' u 2:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', 'data/stiff_k100_blanes_moan_srkn6b_failed.dat' u 2:(1e3) w p lc rgb '#7b4173' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_blanes_moan_srkn6b_predicted.dat' u 1:(1e4) w p lc rgb '#7b4173' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_blanes_moan_srkn14a.dat' u 2:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', 'data/stiff_k100_blanes_moan_srkn14a_failed.dat' u 2:(1e3) w p lc rgb '#000000' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_blanes_moan_srkn14a_predicted.dat' u 1:(1e4) w p lc rgb '#000000' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_aba_10_6_4.dat' u 2:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', 'data/stiff_k100_aba_10_6_4_failed.dat' u 2:(1e3) w p lc rgb '#1f77b4' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_aba_10_6_4_predicted.dat' u 1:(1e4) w p lc rgb '#1f77b4' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_mollified_impulse_sinc.dat' u 2:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', 'data/stiff_k100_mollified_impulse_sinc_failed.dat' u 2:(1e3) w p lc rgb '#d62728' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_mollified_impulse_sinc_predicted.dat' u 1:(1e4) w p lc rgb '#d62728' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_omf4_4mn3f3gp.dat' u 2:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', 'data/stiff_k100_omf4_4mn3f3gp_failed.dat' u 2:(1e3) w p lc rgb '#2ca02c' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_omf4_4mn3f3gp_predicted.dat' u 1:(1e4) w p lc rgb '#2ca02c' pt 11 ps 1.6 notitle, \
  'data/stiff_k100_pmlf6_processed.dat' u 2:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)', 'data/stiff_k100_pmlf6_processed_failed.dat' u 2:(1e3) w p lc rgb '#9467bd' pt 2 ps 2 lw 2 notitle, 'data/stiff_k100_pmlf6_processed_predicted.dat' u 1:(1e4) w p lc rgb '#9467bd' pt 11 ps 1.6 notitle
unset output
