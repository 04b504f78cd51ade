set title 'P3: stellar orbits, epsilon = 0.001: erkn''s explicit methods + peers — error vs cost' noenhanced
set xlabel '∇U evaluations (count)'
set ylabel 'max-norm error of q at t = 10'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_evals.png'
plot 'data/p3_strang.dat' u 4:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4.dat' u 4:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2.dat' u 4:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3.dat' u 4:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4.dat' u 4:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b.dat' u 4:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864.dat' u 4:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064.dat' u 4:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864.dat' u 4:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b.dat' u 4:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a.dat' u 4:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4.dat' u 4:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4.dat' u 4:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4.dat' u 4:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc.dat' u 4:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g.dat' u 4:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g.dat' u 4:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g.dat' u 4:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1.dat' u 4:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2.dat' u 4:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3.dat' u 4:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4.dat' u 4:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4.dat' u 4:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6.dat' u 4:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4.dat' u 4:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet.dat' u 4:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan.dat' u 4:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan.dat' u 4:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4.dat' u 4:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse.dat' u 4:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b.dat' u 4:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a.dat' u 4:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4.dat' u 4:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc.dat' u 4:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp.dat' u 4:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed.dat' u 4:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_evals.svg'
plot 'data/p3_strang.dat' u 4:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4.dat' u 4:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2.dat' u 4:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3.dat' u 4:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4.dat' u 4:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b.dat' u 4:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864.dat' u 4:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064.dat' u 4:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864.dat' u 4:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b.dat' u 4:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a.dat' u 4:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4.dat' u 4:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4.dat' u 4:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4.dat' u 4:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc.dat' u 4:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g.dat' u 4:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g.dat' u 4:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g.dat' u 4:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1.dat' u 4:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2.dat' u 4:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3.dat' u 4:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4.dat' u 4:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4.dat' u 4:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6.dat' u 4:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4.dat' u 4:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet.dat' u 4:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan.dat' u 4:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan.dat' u 4:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4.dat' u 4:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse.dat' u 4:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b.dat' u 4:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a.dat' u 4:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4.dat' u 4:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc.dat' u 4:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp.dat' u 4:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed.dat' u 4:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
unset output
set title 'P3: stellar orbits, epsilon = 0.001: erkn''s explicit methods + peers — error vs CPU time' noenhanced
set xlabel 'CPU time (s)'
set ylabel 'max-norm error of q at t = 10'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_cpu.png'
plot 'data/p3_strang.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b.dat' u 5:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a.dat' u 5:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4.dat' u 5:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4.dat' u 5:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc.dat' u 5:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g.dat' u 5:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet.dat' u 5:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan.dat' u 5:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan.dat' u 5:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse.dat' u 5:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b.dat' u 5:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a.dat' u 5:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4.dat' u 5:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc.dat' u 5:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp.dat' u 5:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed.dat' u 5:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_cpu.svg'
plot 'data/p3_strang.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b.dat' u 5:3 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a.dat' u 5:3 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4.dat' u 5:3 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4.dat' u 5:3 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc.dat' u 5:3 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g.dat' u 5:3 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g.dat' u 5:3 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g.dat' u 5:3 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1.dat' u 5:3 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2.dat' u 5:3 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3.dat' u 5:3 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4.dat' u 5:3 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4.dat' u 5:3 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6.dat' u 5:3 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4.dat' u 5:3 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet.dat' u 5:3 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan.dat' u 5:3 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan.dat' u 5:3 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4.dat' u 5:3 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse.dat' u 5:3 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b.dat' u 5:3 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a.dat' u 5:3 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4.dat' u 5:3 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc.dat' u 5:3 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp.dat' u 5:3 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed.dat' u 5:3 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
unset output
set title 'P3: stellar orbits, epsilon = 0.001: erkn''s explicit methods + peers — energy error, h = 1/10' noenhanced
set xlabel 't_{end} (time units)'
set ylabel 'max_n |H_n − H_0|'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_energy.png'
plot 'data/p3_strang_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4_energy.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4_energy.dat' u 1:2 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b_energy.dat' u 1:2 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864_energy.dat' u 1:2 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064_energy.dat' u 1:2 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864_energy.dat' u 1:2 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b_energy.dat' u 1:2 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a_energy.dat' u 1:2 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4_energy.dat' u 1:2 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4_energy.dat' u 1:2 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4_energy.dat' u 1:2 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc_energy.dat' u 1:2 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g_energy.dat' u 1:2 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g_energy.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3_energy.dat' u 1:2 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4_energy.dat' u 1:2 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4_energy.dat' u 1:2 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6_energy.dat' u 1:2 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4_energy.dat' u 1:2 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet_energy.dat' u 1:2 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan_energy.dat' u 1:2 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan_energy.dat' u 1:2 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4_energy.dat' u 1:2 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse_energy.dat' u 1:2 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b_energy.dat' u 1:2 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a_energy.dat' u 1:2 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc_energy.dat' u 1:2 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'p3_explicit_energy.svg'
plot 'data/p3_strang_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'Strang', \
  'data/p3_yoshida4_energy.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'Yoshida4', \
  'data/p3_saba2_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA2', \
  'data/p3_saba3_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/p3_saba4_energy.dat' u 1:2 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA4', \
  'data/p3_srkn6b_energy.dat' u 1:2 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN6b', \
  'data/p3_aba864_energy.dat' u 1:2 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA864', \
  'data/p3_aba1064_energy.dat' u 1:2 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABA1064', \
  'data/p3_abah864_energy.dat' u 1:2 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'ABAH864', \
  'data/p3_srkn11b_energy.dat' u 1:2 w lp lc rgb '#bcbd22' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN11b', \
  'data/p3_srkn14a_energy.dat' u 1:2 w lp lc rgb '#393b79' dt 1 lw 2.2 pt 7 ps 0.9 t 'SRKN14a', \
  'data/p3_sd9_10_6_4_energy.dat' u 1:2 w lp lc rgb '#637939' dt 1 lw 2.2 pt 7 ps 0.9 t 'SD9(10,6,4)', \
  'data/p3_sdt7_4_energy.dat' u 1:2 w lp lc rgb '#8c6d31' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7(4)', \
  'data/p3_sdt7x_4_energy.dat' u 1:2 w lp lc rgb '#843c39' dt 1 lw 2.2 pt 7 ps 0.9 t 'SDT7x(4)', \
  'data/p3_chinc_energy.dat' u 1:2 w lp lc rgb '#7b4173' dt 1 lw 2.2 pt 7 ps 0.9 t 'ChinC', \
  'data/p3_omf4_3f3g_energy.dat' u 1:2 w lp lc rgb '#000000' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF4(3F3G)', \
  'data/p3_omf6_5f3g_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF6(5F3G)', \
  'data/p3_omf8_11f11g_energy.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'OMF8(11F11G)', \
  'data/p3_sabac1_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC1', \
  'data/p3_sabac2_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC2', \
  'data/p3_sabac3_energy.dat' u 1:2 w lp lc rgb '#ff7f0e' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC3', \
  'data/p3_sabac4_energy.dat' u 1:2 w lp lc rgb '#8c564b' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABAC4', \
  'data/p3_pmlf4_energy.dat' u 1:2 w lp lc rgb '#e377c2' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF4', \
  'data/p3_pmlf6_energy.dat' u 1:2 w lp lc rgb '#17becf' dt 1 lw 2.2 pt 7 ps 0.9 t 'PMLF6', \
  'data/p3_plf7_6_4_energy.dat' u 1:2 w lp lc rgb '#7f7f7f' dt 1 lw 2.2 pt 7 ps 0.9 t 'PLF7_6_4', \
  'data/p3_st_rmer_verlet_energy.dat' u 1:2 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/p3_odeint_sb3a_mclachlan_energy.dat' u 1:2 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/p3_odeint_sb3a_m4_mclachlan_energy.dat' u 1:2 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/p3_gauss2_order_4_energy.dat' u 1:2 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/p3_strang_impulse_energy.dat' u 1:2 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/p3_blanes_moan_srkn6b_energy.dat' u 1:2 w lp lc rgb '#7b4173' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/p3_blanes_moan_srkn14a_energy.dat' u 1:2 w lp lc rgb '#000000' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/p3_aba_10_6_4_energy.dat' u 1:2 w lp lc rgb '#1f77b4' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/p3_mollified_impulse_sinc_energy.dat' u 1:2 w lp lc rgb '#d62728' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/p3_omf4_4mn3f3gp_energy.dat' u 1:2 w lp lc rgb '#2ca02c' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/p3_pmlf6_processed_energy.dat' u 1:2 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
unset output
